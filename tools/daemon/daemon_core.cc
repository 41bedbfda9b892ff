#include "tools/daemon/daemon_core.h"

#include <fstream>
#include <iterator>
#include <sstream>

#include "lcmtypes/message_guard.h"
#include "mfp/terrain_map_t.hpp"
#include "planner/base/check.h"
#include "tools/daemon/message_conversion.h"
#include "tools/daemon/request_validation.h"

namespace mfp {
namespace {

std::string Seconds(double s) {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << s;
  return out.str();
}

}  // namespace

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
  transport.Subscribe(kTerrainMapChannel, [this](const RawMessage& m) { OnMessage(m); });
  transport.Subscribe(kPlanRequestChannel, [this](const RawMessage& m) { OnMessage(m); });
}

void DaemonCore::Log(const std::string& line) const {
  if (log_) log_(line);
}

void DaemonCore::OnMessage(const RawMessage& message) {
  try {
    if (message.channel == kTerrainMapChannel) {
      HandleMap(message);
    } else if (message.channel == kPlanRequestChannel) {
      HandleRequest(message);
    }
  } catch (const std::exception& e) {
    // Handlers turn bad input into statuses; reaching here is a bug or resource
    // exhaustion. Count it and keep running.
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.internal_errors;
    }
    Log("internal error handling " + message.channel + ": " + e.what());
  }
}

void DaemonCore::HandleMap(const RawMessage& message) {
  size_t max_bytes = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    max_bytes = setup_->config.limits.max_map_bytes;
  }
  terrain_map_t map;
  const std::string error = DecodeGuarded(message.data, message.size, max_bytes, &map);
  if (!error.empty()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.rejected_messages;
    }
    Log("rejected message on " + message.channel + ": " + error);
    return;
  }
  const std::string bytes(map.data.begin(), map.data.end());
  map.data.clear();
  try {
    AcceptMap(bytes, map.format, map.frame, map.utime,
              "terrain_map_t utime " + std::to_string(map.utime));
  } catch (const InputError& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.rejected_maps;
    }
    Log(std::string("rejected map: ") + e.what());
  }
}

void DaemonCore::LoadMapFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("initial_map: cannot open '" + path + "'");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t dot = path.rfind('.');
  const std::string format = dot == std::string::npos ? "" : path.substr(dot + 1);
  AcceptMap(bytes, format, "world", clock_(), path);
}

void DaemonCore::AcceptMap(const std::string& bytes, const std::string& format,
                           const std::string& frame, int64_t map_utime, const std::string& what) {
  MapFunction map_function;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    map_function = map_function_;
  }
  // Extraction runs outside the lock: requests keep being answered meanwhile.
  auto regions =
      std::make_shared<const std::vector<ConvexRegion>>(map_function(bytes, format, what));
  const int64_t now = clock_();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    regions_ = regions;
    map_utime_ = map_utime;
    map_receive_utime_ = now;
    ++counters_.maps;
  }
  PublishMessage(publisher_, kRegionsChannel, ToRegionSetMessage(*regions, frame, now, map_utime));
  Log("map accepted (" + what + "): " + std::to_string(bytes.size()) + " bytes, " +
      std::to_string(regions->size()) + " regions");
}

void DaemonCore::HandleRequest(const RawMessage& message) {
  std::shared_ptr<const DaemonSetup> setup;
  std::shared_ptr<const std::vector<ConvexRegion>> regions;
  int64_t map_utime = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    setup = setup_;
    regions = regions_;
    map_utime = map_utime_;
  }
  plan_request_t request;
  const std::string error =
      DecodeGuarded(message.data, message.size, setup->config.limits.max_request_bytes, &request);
  if (!error.empty()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.rejected_messages;
    }
    Log("rejected message on " + message.channel + ": " + error);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.requests;
  }
  const ValidatedRequest checked =
      ValidateRequest(request, setup->robots, setup->config.default_robot, regions.get(),
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
  queued.receive_utime = clock_();
  std::optional<QueuedRequest> evicted;
  size_t capacity = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    evicted = queue_.Push(std::move(queued));
    capacity = queue_.capacity();
  }
  work_available_.notify_one();
  if (evicted) {
    ReplyDropped(*evicted, "dropped: the queue of " + std::to_string(capacity) +
                               " requests was full and newer requests are planned first");
  }
}

bool DaemonCore::PlanNext() {
  std::optional<QueuedRequest> next;
  std::shared_ptr<const DaemonSetup> setup;
  std::shared_ptr<const std::vector<ConvexRegion>> regions;
  int64_t map_utime = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return false;
    next = queue_.PopNewest();
    if (!next) return false;
    setup = setup_;
    regions = regions_;
    map_utime = map_utime_;
    planning_ = true;
  }
  const auto robot = setup->robots.find(next->robot_name);
  Plan plan;
  if (robot == setup->robots.end()) {
    // The robot went away with a config reload after the request was queued.
    plan.status = SolveStatus::kInvalidRequest;
    plan.message = "robot: '" + next->robot_name + "' is no longer configured";
  } else {
    try {
      plan = plan_function_(robot->second, *regions, next->request, setup->config.planner);
    } catch (const InputError& e) {
      plan = Plan();
      plan.status = SolveStatus::kInvalidRequest;
      plan.message = e.what();
    } catch (const std::exception& e) {
      plan = Plan();
      plan.status = SolveStatus::kInternalError;
      plan.message = std::string("planner failed: ") + e.what();
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    planning_ = false;
    counters_.last_solve_time_s = plan.solve_time_s;
    if (plan.status == SolveStatus::kInternalError) ++counters_.internal_errors;
  }
  Log("request " + std::to_string(next->request_id) + " planned: " + ToString(plan.status) +
      ", " + std::to_string(plan.footsteps.size()) + " footsteps, " + Seconds(plan.solve_time_s) +
      " s" + (plan.message.empty() ? "" : " (" + plan.message + ")"));
  Reply(ToPlanMessage(plan, next->request_id, next->robot_name, clock_(), map_utime));
  return true;
}

bool DaemonCore::WaitAndPlanNext(std::chrono::milliseconds timeout) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!work_available_.wait_for(lock, timeout, [this] { return stopped_ || !queue_.empty(); }))
      return false;
    if (stopped_) return false;
  }
  return PlanNext();
}

void DaemonCore::Reply(const plan_t& reply) {
  {
    // Counted first, so no status published after a client saw the reply lags behind it.
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.plans;
  }
  PublishMessage(publisher_, kPlanChannel, reply);
}

void DaemonCore::ReplyDropped(const QueuedRequest& request, const std::string& why) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.dropped_requests;
  }
  Log("request " + std::to_string(request.request_id) + " " + why);
  Reply(StatusReply(SolveStatus::kDropped, why, request.request_id, request.robot_name, clock_(),
                    0));
}

status_t DaemonCore::StatusMessage() const {
  const int64_t now = clock_();
  std::lock_guard<std::mutex> lock(mutex_);
  status_t s;
  s.utime = now;
  // Copies of the constants: lcm-gen declares them without a definition to bind to.
  const int8_t no_map = status_t::STATE_NO_MAP, planning = status_t::STATE_PLANNING,
               idle = status_t::STATE_IDLE;
  s.state = regions_ == nullptr ? no_map : planning_ ? planning : idle;
  s.requests = counters_.requests;
  s.plans = counters_.plans;
  s.rejected_messages = counters_.rejected_messages;
  s.invalid_requests = counters_.invalid_requests;
  s.dropped_requests = counters_.dropped_requests;
  s.maps = counters_.maps;
  s.rejected_maps = counters_.rejected_maps;
  s.queue_length = static_cast<int32_t>(queue_.size());
  s.num_regions = regions_ == nullptr ? 0 : static_cast<int32_t>(regions_->size());
  s.last_solve_time_s = counters_.last_solve_time_s;
  s.map_age_s = regions_ == nullptr ? -1.0 : 1e-6 * static_cast<double>(now - map_receive_utime_);
  s.uptime_s = 1e-6 * static_cast<double>(now - start_utime_);
  std::ostringstream msg;
  msg << (regions_ == nullptr ? "waiting for a map" : planning_ ? "planning" : "idle")
      << "; requests " << s.requests << ", plans " << s.plans << ", rejected messages "
      << s.rejected_messages << ", invalid " << s.invalid_requests << ", dropped "
      << s.dropped_requests << ", internal errors " << counters_.internal_errors;
  s.message = msg.str();
  return s;
}

void DaemonCore::PublishStatus() { PublishMessage(publisher_, kStatusChannel, StatusMessage()); }

void DaemonCore::Reconfigure(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function) {
  std::deque<QueuedRequest> evicted;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    setup_ = std::move(setup);
    if (map_function) map_function_ = std::move(map_function);
    evicted = queue_.SetCapacity(static_cast<size_t>(setup_->config.limits.queue_size));
  }
  for (const QueuedRequest& r : evicted) ReplyDropped(r, "dropped: the queue shrank on reload");
}

void DaemonCore::Stop() {
  std::vector<QueuedRequest> pending;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    while (auto r = queue_.PopNewest()) pending.push_back(std::move(*r));
  }
  work_available_.notify_all();
  for (const QueuedRequest& r : pending) ReplyDropped(r, "dropped: the daemon is stopping");
}

DaemonCounters DaemonCore::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

size_t DaemonCore::queue_length() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

}  // namespace mfp
