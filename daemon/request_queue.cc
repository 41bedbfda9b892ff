#include "daemon/internal/request_queue.h"

#include "base/check.h"

namespace mfp {

RequestQueue::RequestQueue(size_t capacity) : capacity_(capacity) { MFP_CHECK(capacity > 0); }

std::optional<QueuedRequest> RequestQueue::Push(QueuedRequest request) {
  std::optional<QueuedRequest> evicted;
  if (entries_.size() >= capacity_) {
    evicted = std::move(entries_.front());
    entries_.pop_front();
  }
  entries_.push_back(std::move(request));
  return evicted;
}

std::optional<QueuedRequest> RequestQueue::PopNewest() {
  if (entries_.empty()) return std::nullopt;
  QueuedRequest newest = std::move(entries_.back());
  entries_.pop_back();
  return newest;
}

std::vector<QueuedRequest> RequestQueue::RemoveRobot(const std::string& robot_name) {
  std::vector<QueuedRequest> removed;
  std::deque<QueuedRequest> kept;
  for (QueuedRequest& r : entries_) {
    if (r.robot_name == robot_name) {
      removed.push_back(std::move(r));
    } else {
      kept.push_back(std::move(r));
    }
  }
  entries_.swap(kept);
  return removed;
}

std::deque<QueuedRequest> RequestQueue::SetCapacity(size_t capacity) {
  MFP_CHECK(capacity > 0);
  capacity_ = capacity;
  std::deque<QueuedRequest> evicted;
  while (entries_.size() > capacity_) {
    evicted.push_back(std::move(entries_.front()));
    entries_.pop_front();
  }
  return evicted;
}

}  // namespace mfp
