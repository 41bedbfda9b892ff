#include "daemon/daemon_runner.h"

#include <chrono>

namespace mfp {

DaemonRunner::DaemonRunner(DaemonCore& core, Transport& transport, double heartbeat_period_s)
    : core_(core), transport_(transport), heartbeat_period_s_(heartbeat_period_s) {
  receive_thread_ = std::thread([this] { ReceiveLoop(); });
  work_thread_ = std::thread([this] { WorkLoop(); });
  intake_thread_ = std::thread([this] { IntakeLoop(); });
  map_thread_ = std::thread([this] { MapLoop(); });
  heartbeat_thread_ = std::thread([this] { HeartbeatLoop(); });
}

DaemonRunner::~DaemonRunner() { Stop(); }

void DaemonRunner::SetHeartbeatPeriod(double seconds) {
  heartbeat_period_s_ = seconds;
  heartbeat_wake_.notify_all();
}

void DaemonRunner::Stop() {
  if (stop_.exchange(true)) return;
  core_.Stop();
  heartbeat_wake_.notify_all();
  work_thread_.join();
  intake_thread_.join();
  map_thread_.join();
  receive_thread_.join();
  heartbeat_thread_.join();
  core_.PublishStatus();
}

void DaemonRunner::ReceiveLoop() {
  while (!stop_) {
    // A short timeout bounds the time Stop() waits for this thread.
    if (transport_.HandleTimeout(20) < 0 && !stop_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
}

void DaemonRunner::WorkLoop() {
  while (!stop_) core_.WaitAndPlanNext(std::chrono::milliseconds(200));
}

void DaemonRunner::IntakeLoop() {
  while (!stop_) core_.ProcessNextReceived(std::chrono::milliseconds(200));
}

void DaemonRunner::MapLoop() {
  while (!stop_) core_.ProcessPendingMap(std::chrono::milliseconds(200));
}

void DaemonRunner::HeartbeatLoop() {
  std::unique_lock<std::mutex> lock(heartbeat_mutex_);
  while (!stop_) {
    lock.unlock();
    core_.PublishStatus();
    lock.lock();
    const auto period = std::chrono::duration<double>(heartbeat_period_s_.load());
    heartbeat_wake_.wait_for(lock, period, [this] { return stop_.load(); });
  }
}

}  // namespace mfp
