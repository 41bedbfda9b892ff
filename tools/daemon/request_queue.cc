#include "tools/daemon/request_queue.h"

#include "planner/base/check.h"

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
