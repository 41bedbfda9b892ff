#pragma once
// Runs a DaemonCore live: a receive thread handles the transport, a worker thread plans
// (so the heartbeat never waits for a solve), a heartbeat thread publishes status_t.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "lcmtypes/transport.h"
#include "tools/daemon/daemon_core.h"

namespace mfp {

class DaemonRunner {
 public:
  // The core must already be subscribed to the transport. Both outlive the runner.
  DaemonRunner(DaemonCore& core, Transport& transport, double heartbeat_period_s);
  ~DaemonRunner();  // Stop()s
  DaemonRunner(const DaemonRunner&) = delete;
  DaemonRunner& operator=(const DaemonRunner&) = delete;

  void SetHeartbeatPeriod(double seconds);

  // Stops the threads: answers queued requests as dropped, waits for a plan in progress
  // to finish, publishes a last status. Idempotent.
  void Stop();

 private:
  void ReceiveLoop();
  void WorkLoop();
  void HeartbeatLoop();

  DaemonCore& core_;
  Transport& transport_;
  std::atomic<bool> stop_{false};
  std::atomic<double> heartbeat_period_s_;
  std::mutex heartbeat_mutex_;
  std::condition_variable heartbeat_wake_;
  std::thread receive_thread_;
  std::thread work_thread_;
  std::thread heartbeat_thread_;
};

}  // namespace mfp
