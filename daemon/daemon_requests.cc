// DaemonCore's request handling: decode, validate and queue a request, and the replies
// that answer a request without a plan.
#include "daemon/daemon_core.h"

#include "daemon/internal/request_validation.h"
#include "daemon/message_conversion.h"
#include "lcmtypes/message_guard.h"

namespace mfp {
namespace {

// LCM strings end at their first NUL byte (the encoder writes strlen bytes while the
// size counts them all, and the message fails to encode): write NUL as "\0".
std::string WithoutNul(const std::string& s) {
  if (s.find('\0') == std::string::npos) return s;
  std::string out;
  for (char c : s) {
    if (c == '\0') {
      out += "\\0";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

void DaemonCore::HandleRequest(const RawMessage& message, int64_t arrival_utime) {
  std::shared_ptr<const DaemonSetup> setup;
  std::shared_ptr<const std::vector<ConvexRegion>> regions;
  std::shared_ptr<const SeenSurface> seen_surface;
  int64_t map_utime = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    setup = setup_;
    regions = regions_;
    seen_surface = seen_surface_;
    map_utime = map_utime_;
  }
  plan_request_t request;
  const std::string error =
      DecodeGuarded(message.data, message.size, setup->config.limits.max_request_bytes, &request);
  if (!error.empty()) {
    CountRejected(message.channel, error);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.requests;
  }
  const ValidatedRequest checked =
      ValidateRequest(request, setup->robots, setup->config.default_robot, regions.get(), seen_surface,
                      setup->config.limits, setup->config.planner);
  if (!checked.ok) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.invalid_requests;
    }
    Log("request " + std::to_string(request.request_id) + " rejected (" +
        ToString(checked.status) + "): " + checked.message);
    Reply(StatusReply(checked.status, checked.message, request.request_id, checked.robot_name,
                      clock_(), map_utime));
    return;
  }
  QueuedRequest queued;
  queued.request_id = request.request_id;
  queued.robot_name = checked.robot_name;
  queued.request = checked.request;
  queued.receive_utime = arrival_utime;
  std::optional<QueuedRequest> evicted;
  std::vector<QueuedRequest> superseded;
  size_t capacity = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (setup->config.limits.supersede_same_robot) {
      superseded = queue_.RemoveRobot(queued.robot_name);
      counters_.superseded_requests += static_cast<int64_t>(superseded.size());
    }
    evicted = queue_.Push(std::move(queued));
    capacity = queue_.capacity();
  }
  work_available_.notify_one();
  for (const QueuedRequest& old : superseded) {
    ReplyStatus(old, SolveStatus::kSuperseded,
                "superseded by request " + std::to_string(request.request_id) +
                    " for the same robot, which is planned instead");
  }
  if (evicted) {
    ReplyStatus(*evicted, SolveStatus::kDropped,
                "dropped: the queue of " + std::to_string(capacity) +
                    " requests was full and newer requests are planned first");
  }
}

void DaemonCore::AnswerUnplanned(const Received& received, const std::string& why) {
  size_t max_bytes = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    max_bytes = setup_->config.limits.max_request_bytes;
  }
  plan_request_t request;
  const std::string error =
      DecodeGuarded(received.bytes.data(), received.bytes.size(), max_bytes, &request);
  if (!error.empty()) {
    CountRejected(received.channel, error);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.requests;
  }
  QueuedRequest r;
  r.request_id = request.request_id;
  r.robot_name = request.robot;
  ReplyStatus(r, SolveStatus::kDropped, why);
}

void DaemonCore::Reply(plan_t reply) {
  reply.robot = WithoutNul(reply.robot);
  reply.message = WithoutNul(reply.message);
  {
    // Counted first, so no status published after a client saw the reply lags behind it.
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.plans;
  }
  if (PublishMessage(publisher_, kPlanChannel, reply)) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    --counters_.plans;
    ++counters_.publish_failures;
  }
  Log("request " + std::to_string(reply.request_id) + ": its reply could not be published (" +
      std::to_string(reply.getEncodedSize()) + " bytes)");
}

void DaemonCore::ReplyStatus(const QueuedRequest& request, SolveStatus status,
                             const std::string& why) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status == SolveStatus::kDropped) ++counters_.dropped_requests;
  }
  Log("request " + std::to_string(request.request_id) + " answered " + ToString(status) + " (" +
      why + ")");
  Reply(StatusReply(status, why, request.request_id, request.robot_name, clock_(), 0));
}

}  // namespace mfp
