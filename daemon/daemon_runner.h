#pragma once
// Runs a DaemonCore live: a receive thread handles the transport and only copies
// messages into the core's intake queue, an intake thread decodes and validates them, a
// map thread extracts regions, a worker thread plans (so neither receiving nor the
// heartbeat ever waits for a solve or an extraction), a heartbeat thread publishes
// status_t.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "daemon/daemon_core.h"
#include "lcmtypes/transport.h"

namespace mfp {

class DaemonRunner {
 public:
  // The core must already be subscribed to the transport. Both outlive the runner.
  DaemonRunner(DaemonCore& core, Transport& transport, double heartbeat_period_s);
  ~DaemonRunner();  // Stop()s
  DaemonRunner(const DaemonRunner&) = delete;
  DaemonRunner& operator=(const DaemonRunner&) = delete;

  void SetHeartbeatPeriod(double seconds);

  // Stops the threads: answers queued and received requests as dropped, abandons a plan
  // or extraction in progress (its request answered dropped), publishes a last status.
  // Returns within a few tens of milliseconds. Idempotent.
  void Stop();

 private:
  void ReceiveLoop();
  void WorkLoop();
  void IntakeLoop();
  void MapLoop();
  void HeartbeatLoop();

  DaemonCore& core_;
  Transport& transport_;
  std::atomic<bool> stop_{false};
  std::atomic<double> heartbeat_period_s_;
  std::mutex heartbeat_mutex_;
  std::condition_variable heartbeat_wake_;
  std::thread receive_thread_;
  std::thread work_thread_;
  std::thread intake_thread_;
  std::thread map_thread_;
  std::thread heartbeat_thread_;
};

}  // namespace mfp
