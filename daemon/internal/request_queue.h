#pragma once
// A bounded queue of accepted requests served newest first. Pushing into a full queue
// evicts the oldest entry and hands it back so the caller can reply to it (status
// dropped): nothing waits forever and the queue never grows past its capacity.
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "planner/planning/footstep_planner.h"

namespace mfp {

struct QueuedRequest {
  int64_t request_id = 0;
  std::string robot_name;
  PlanRequest request;
  int64_t receive_utime = 0;  // arrival: its deadline is this plus request.time_limit_s [us]
};

class RequestQueue {
 public:
  explicit RequestQueue(size_t capacity);

  // Adds a request; returns the evicted oldest one when the queue was full.
  std::optional<QueuedRequest> Push(QueuedRequest request);
  // Removes and returns the newest request; nullopt when empty.
  std::optional<QueuedRequest> PopNewest();
  // Removes and returns every entry for this robot, oldest first.
  std::vector<QueuedRequest> RemoveRobot(const std::string& robot_name);
  // Changes the capacity; returns the evicted oldest entries, if any.
  std::deque<QueuedRequest> SetCapacity(size_t capacity);

  size_t size() const { return entries_.size(); }
  size_t capacity() const { return capacity_; }
  bool empty() const { return entries_.empty(); }

 private:
  size_t capacity_;
  std::deque<QueuedRequest> entries_;  // oldest at the front
};

}  // namespace mfp
