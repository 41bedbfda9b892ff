// DaemonCore's set-up and lifecycle, and the intake: receiving messages, handing them
// to the intake and map threads, reload and stop. Maps, requests, planning and status
// have files of their own (daemon_maps.cc, daemon_requests.cc, daemon_planning.cc,
// daemon_status.cc).
#include "daemon/daemon_core.h"

#include <algorithm>

#include "base/check.h"
#include "base/format.h"
#include "daemon/heap_release.h"
#include "lcmtypes/message_guard.h"

namespace mfp {

DaemonCore::DaemonCore(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function,
                       PlanFunction plan_function, Publisher& publisher, Clock clock, LogSink log)
    : plan_function_(std::move(plan_function)),
      publisher_(publisher),
      clock_(std::move(clock)),
      log_(std::move(log)),
      start_utime_(clock_()),
      setup_(std::move(setup)),
      map_function_(std::move(map_function)),
      queue_(static_cast<size_t>(setup_->config.limits.queue_size)) {
  MFP_CHECK(map_function_ && plan_function_ && clock_);
}

void DaemonCore::SubscribeTo(Transport& transport) {
  transport.Subscribe(kTerrainMapChannel, [this](const RawMessage& m) { Receive(m); });
  transport.Subscribe(kHeightMapChannel, [this](const RawMessage& m) { Receive(m); });
  transport.Subscribe(kPlanRequestChannel, [this](const RawMessage& m) { Receive(m); });
}

void DaemonCore::Log(const std::string& line) const {
  if (log_) log_(EscapedText(line));  // one line, whatever names it quotes
}

void DaemonCore::CountPublishFailure(const std::string& channel) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.publish_failures;
  }
  Log("publish failed on " + channel + " (the message did not encode or the transport refused it)");
}

// Handlers turn bad input into statuses; reaching here is a bug or resource exhaustion.
// Count it and keep running.
void DaemonCore::CountInternalError(const std::string& doing, const std::exception& e) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.internal_errors;
  }
  Log("internal error " + doing + ": " + e.what());
}

void DaemonCore::CountRejected(const std::string& channel, const std::string& error) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.rejected_messages;
  }
  Log("rejected message on " + channel + ": " + error);
}

void DaemonCore::Receive(const RawMessage& message) {
  try {
    const bool is_map = message.channel == kTerrainMapChannel || message.channel == kHeightMapChannel;
    if (!is_map && message.channel != kPlanRequestChannel) return;
    Received received;
    received.channel = message.channel;
    received.arrival_utime = clock_();
    size_t cap = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      cap = is_map ? setup_->config.limits.max_map_bytes : setup_->config.limits.max_request_bytes;
    }
    if (message.size > cap) {
      // The guarded decoder would refuse it too; refusing here saves the copy.
      CountRejected(message.channel, std::to_string(message.size) + " bytes exceed the limit of " +
                                         std::to_string(cap) + " bytes");
      return;
    }
    received.bytes.assign(message.data, message.data + message.size);
    std::optional<Received> overflow;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopped_) {
        overflow = std::move(received);
      } else if (is_map) {
        if (pending_map_) ++counters_.superseded_maps;
        pending_map_ = std::move(received);
      } else if (received_.size() >= static_cast<size_t>(setup_->config.limits.inbox_size)) {
        ++counters_.inbox_overflows;
        overflow = std::move(received);
      } else {
        received_.push_back(std::move(received));
      }
    }
    if (overflow) {
      if (!is_map) AnswerUnplanned(*overflow, stopped_ ? "dropped: the daemon is stopping"
                                                       : "dropped: the intake queue was full");
      return;
    }
    (is_map ? map_available_ : received_available_).notify_one();
  } catch (const std::exception& e) {
    CountInternalError("receiving on " + message.channel, e);
  }
}

bool DaemonCore::ProcessNextReceived(std::chrono::milliseconds timeout) {
  Received next;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!received_available_.wait_for(lock, timeout,
                                       [this] { return stopped_ || !received_.empty(); }))
      return false;
    if (stopped_) return false;
    next = std::move(received_.front());
    received_.pop_front();
  }
  try {
    HandleRequest(next.AsRaw(), next.arrival_utime);
  } catch (const std::exception& e) {
    CountInternalError("handling " + next.channel, e);
  }
  return true;
}

bool DaemonCore::ProcessPendingMap(std::chrono::milliseconds timeout) {
  Received next;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!map_available_.wait_for(lock, timeout, [this] { return stopped_ || pending_map_; }))
      return false;
    if (stopped_) return false;
    next = std::move(*pending_map_);
    pending_map_.reset();
  }
  try {
    HandleMap(next.AsRaw(), /*abandon_on_stop=*/true);
  } catch (const std::exception& e) {
    CountInternalError("handling " + next.channel, e);
  }
  next = Received();  // the map's bytes freed too, then the extraction's leftovers returned
  ReleaseFreeHeap();
  return true;
}

void DaemonCore::OnMessage(const RawMessage& message) {
  try {
    if (message.channel == kTerrainMapChannel || message.channel == kHeightMapChannel) {
      HandleMap(message, /*abandon_on_stop=*/false);
      ReleaseFreeHeap();
    } else if (message.channel == kPlanRequestChannel) {
      HandleRequest(message, clock_());
    }
  } catch (const std::exception& e) {
    CountInternalError("handling " + message.channel, e);
  }
}

void DaemonCore::Reconfigure(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function) {
  std::deque<QueuedRequest> evicted;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    setup_ = std::move(setup);
    if (map_function) map_function_ = std::move(map_function);
    last_plans_.clear();  // the robots may have changed
    evicted = queue_.SetCapacity(static_cast<size_t>(setup_->config.limits.queue_size));
  }
  for (const QueuedRequest& r : evicted)
    ReplyStatus(r, SolveStatus::kDropped, "dropped: the queue shrank on reload");
}

void DaemonCore::Stop() {
  std::vector<QueuedRequest> pending;
  std::deque<Received> received;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    while (auto r = queue_.PopNewest()) pending.push_back(std::move(*r));
    received.swap(received_);
    pending_map_.reset();
  }
  work_available_.notify_all();
  received_available_.notify_all();
  map_available_.notify_all();
  for (const QueuedRequest& r : pending)
    ReplyStatus(r, SolveStatus::kDropped, "dropped: the daemon is stopping");
  for (const Received& r : received) AnswerUnplanned(r, "dropped: the daemon is stopping");
}

DaemonCounters DaemonCore::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  DaemonCounters c = counters_;
  // Those still running now, less the one being waited for.
  c.abandoned_plans_running = std::max(0, plan_tasks_->load() - (planning_ ? 1 : 0));
  return c;
}

void DaemonCore::SetTaskLauncher(TaskLauncher launcher) {
  MFP_CHECK(launcher);
  std::lock_guard<std::mutex> lock(mutex_);
  launcher_ = std::move(launcher);
}

size_t DaemonCore::queue_length() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

}  // namespace mfp
