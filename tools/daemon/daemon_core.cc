#include "tools/daemon/daemon_core.h"

#include <atomic>

#include <fstream>
#include <iterator>
#include <sstream>

#include "lcmtypes/message_guard.h"
#include "mfp/terrain_map_t.hpp"
#include "planner/base/check.h"
#include "planner/base/deadline.h"
#include "tools/daemon/abandonable_task.h"
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
  transport.Subscribe(kTerrainMapChannel, [this](const RawMessage& m) { Receive(m); });
  transport.Subscribe(kHeightMapChannel, [this](const RawMessage& m) { Receive(m); });
  transport.Subscribe(kPlanRequestChannel, [this](const RawMessage& m) { Receive(m); });
}

void DaemonCore::Log(const std::string& line) const {
  if (log_) log_(line);
}

template <class Message>
void DaemonCore::Publish(const std::string& channel, const Message& message) {
  if (PublishMessage(publisher_, channel, message)) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.publish_failures;
  }
  Log("publish failed on " + channel + " (the message did not encode or the transport refused it)");
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
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.internal_errors;
    }
    Log("internal error receiving on " + message.channel + ": " + e.what());
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
  RawMessage raw;
  raw.channel = next.channel;
  raw.data = next.bytes.data();
  raw.size = next.bytes.size();
  try {
    HandleRequest(raw, next.arrival_utime);
  } catch (const std::exception& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.internal_errors;
    }
    Log("internal error handling " + raw.channel + ": " + e.what());
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
  RawMessage raw;
  raw.channel = next.channel;
  raw.data = next.bytes.data();
  raw.size = next.bytes.size();
  try {
    HandleMap(raw, /*abandon_on_stop=*/true);
  } catch (const std::exception& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.internal_errors;
    }
    Log("internal error handling " + raw.channel + ": " + e.what());
  }
  return true;
}

void DaemonCore::OnMessage(const RawMessage& message) {
  try {
    if (message.channel == kTerrainMapChannel || message.channel == kHeightMapChannel) {
      HandleMap(message, /*abandon_on_stop=*/false);
    } else if (message.channel == kPlanRequestChannel) {
      HandleRequest(message, clock_());
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

void DaemonCore::HandleMap(const RawMessage& message, bool abandon_on_stop) {
  if (message.channel == kHeightMapChannel) return HandleHeightMap(message, abandon_on_stop);
  size_t max_bytes = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    max_bytes = setup_->config.limits.max_map_bytes;
  }
  terrain_map_t map;
  const std::string error = DecodeGuarded(message.data, message.size, max_bytes, &map);
  if (!error.empty()) {
    CountRejected(message.channel, error);
    return;
  }
  const std::string bytes(map.data.begin(), map.data.end());
  map.data.clear();
  try {
    AcceptMap(bytes, map.format, map.frame, map.utime,
              "terrain_map_t utime " + std::to_string(map.utime), abandon_on_stop);
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
  AcceptMap(bytes, format, "world", clock_(), path, /*abandon_on_stop=*/false);
}

void DaemonCore::AcceptMap(const std::string& bytes, const std::string& format,
                           const std::string& frame, int64_t map_utime, const std::string& what,
                           bool abandon_on_stop) {
  MapFunction map_function;
  bool accept_empty = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    map_function = map_function_;
    accept_empty = setup_->config.limits.accept_empty_maps;
    extracting_ = true;
  }
  // Extraction runs outside the lock: requests keep being answered meanwhile.
  std::optional<std::vector<ConvexRegion>> extracted;
  try {
    if (abandon_on_stop) {
      // On a thread of its own that a stop stops waiting for (the extractor has no stop
      // flag of its own yet).
      AbandonableTask<std::vector<ConvexRegion>> task(
          [map_function, bytes, format, what] { return map_function(bytes, format, what); });
      extracted = task.Wait(std::chrono::steady_clock::time_point::max(), stopped_);
    } else {
      extracted = map_function(bytes, format, what);
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    extracting_ = false;
    throw;
  }
  const int64_t now = clock_();
  std::shared_ptr<const std::vector<ConvexRegion>> regions;
  size_t kept_regions = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    extracting_ = false;
    if (!extracted) {
      // Only a stop ends the wait without a result.
    } else if (extracted->empty() && !accept_empty && regions_ != nullptr && !regions_->empty()) {
      ++counters_.empty_maps;
      kept_regions = regions_->size();
    } else {
      regions = std::make_shared<const std::vector<ConvexRegion>>(std::move(*extracted));
      regions_ = regions;
      map_utime_ = map_utime;
      last_plans_.clear();
      map_receive_utime_ = now;
      ++counters_.maps;
    }
  }
  if (!extracted) {
    Log("map extraction abandoned (" + what + "): the daemon is stopping");
    return;
  }
  if (regions == nullptr) {
    Log("map refused (" + what + "): it has no regions; the current map (" +
        std::to_string(kept_regions) +
        " regions) stays (set limits.accept_empty_maps to take such maps)");
    return;
  }
  Publish(kRegionsChannel, ToRegionSetMessage(*regions, frame, now, map_utime));
  Log("map accepted (" + what + "): " + std::to_string(bytes.size()) + " bytes, " +
      std::to_string(regions->size()) + " regions");
}

void DaemonCore::HandleRequest(const RawMessage& message, int64_t arrival_utime) {
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
    CountRejected(message.channel, error);
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

bool DaemonCore::PlanNext() {
  std::optional<QueuedRequest> next;
  std::shared_ptr<const DaemonSetup> setup;
  std::shared_ptr<const std::vector<ConvexRegion>> regions;
  int64_t map_utime = 0;
  std::vector<std::vector<Footstep>> warm_start;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return false;
    next = queue_.PopNewest();
    if (!next) return false;
    setup = setup_;
    regions = regions_;
    map_utime = map_utime_;
    planning_ = true;
    if (setup->config.limits.warm_start_plans > 0) {
      // Also for a new goal: the plan's steps are then only a proposal the search weighs.
      const auto last = last_plans_.find(next->robot_name);
      if (last != last_plans_.end()) warm_start = last->second;
    }
  }
  // The deadline counts from the request's arrival: time spent queued is spent.
  const double limit_s = next->request.time_limit_s > 0 ? next->request.time_limit_s
                                                        : setup->config.planner.default_time_limit_s;
  const double waited_s = 1e-6 * static_cast<double>(clock_() - next->receive_utime);
  const double remaining_s = limit_s - waited_s;
  const double margin_s = setup->config.limits.reply_margin_s;
  const auto robot = setup->robots.find(next->robot_name);
  Plan plan;
  bool abandoned = false;
  if (remaining_s <= margin_s) {
    plan.status = SolveStatus::kTimeLimit;
    plan.message = "deadline passed in the queue: waited " + Seconds(waited_s) + " s of its " +
                   Seconds(limit_s) + " s time limit";
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.expired_requests;
  } else if (robot == setup->robots.end()) {
    // The robot went away with a config reload after the request was queued.
    plan.status = SolveStatus::kInvalidRequest;
    plan.message = "robot: '" + next->robot_name + "' is no longer configured";
  } else {
    PlanRequest request = next->request;
    request.time_limit_s = remaining_s - margin_s;
    request.warm_start = std::move(warm_start);
    // The planner checks this flag inside its solves: set when the core stops waiting
    // (a stop, or the deadline passed), so an abandoned plan ends at its next check
    // instead of running on. The task holds the flag, so it outlives the core's wait.
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    request.deadline = Deadline::After(remaining_s - margin_s).WithStop(cancel.get());
    // The plan accepted so far (window by window): the watchdog's answer at the deadline.
    struct SoFar {
      std::mutex mutex;
      std::optional<Plan> plan;
    };
    auto so_far = std::make_shared<SoFar>();
    request.on_plan_so_far = [so_far](const Plan& p) {
      std::lock_guard<std::mutex> lock(so_far->mutex);
      so_far->plan = p;
    };
    // The task owns what it reads (setup and regions by shared pointer), so a plan left
    // running after its deadline or a stop touches nothing of the core's.
    AbandonableTask<Plan> task([plan_function = plan_function_, setup, regions,
                                robot = &robot->second, request, cancel] {
      return plan_function(*robot, *regions, request, setup->config.planner);
    });
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(remaining_s));
    try {
      std::optional<Plan> result = task.Wait(deadline, stopped_);
      if (!result) cancel->store(true);
      if (result) {
        plan = std::move(*result);
      } else if (stopped_) {
        plan.status = SolveStatus::kDropped;
        plan.message = "dropped: the daemon is stopping; the plan in progress was abandoned";
        abandoned = true;
      } else {
        const std::string why = " by the deadline (" + Seconds(limit_s) + " s from arrival, " +
                                Seconds(waited_s) + " s of it queued)";
        {
          std::lock_guard<std::mutex> lock(so_far->mutex);
          if (so_far->plan) plan = *so_far->plan;
        }
        if (plan.footsteps.empty()) {
          plan.status = SolveStatus::kTimeLimit;
          plan.message = "the planner had no plan" + why;
        } else {
          // Anytime: the windows accepted so far, each step valid. Counted as a time-limit ending.
          plan.message = "the planner had not finished" + why + "; " + plan.message;
          plan.solve_time_s = 1e-6 * static_cast<double>(clock_() - next->receive_utime);
          std::lock_guard<std::mutex> lock(mutex_);
          ++counters_.time_limit_endings;
        }
        abandoned = true;
      }
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
    if (plan.status == SolveStatus::kTimeLimit) ++counters_.time_limit_endings;
    if (plan.status == SolveStatus::kDropped) ++counters_.dropped_requests;
    if (abandoned) ++counters_.abandoned_solves;
    // Only a plan on the map still current: a map that arrived meanwhile cleared the rest.
    if (HasPlan(plan.status) && regions == regions_ && setup->config.limits.warm_start_plans > 0) {
      std::vector<std::vector<Footstep>>& plans = last_plans_[next->robot_name];
      plans.insert(plans.begin(), plan.footsteps);
      plans.resize(std::min(plans.size(), static_cast<size_t>(setup->config.limits.warm_start_plans)));
    }
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

void DaemonCore::SetUdpErrorSource(std::function<int64_t()> source) {
  std::lock_guard<std::mutex> lock(mutex_);
  udp_errors_ = std::move(source);
}

status_t DaemonCore::StatusMessage() const {
  const int64_t now = clock_();
  std::function<int64_t()> udp_errors;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    udp_errors = udp_errors_;
  }
  const int64_t udp = udp_errors ? udp_errors() : -1;
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
  s.queue_length = static_cast<int32_t>(queue_.size() + received_.size());
  s.num_regions = regions_ == nullptr ? 0 : static_cast<int32_t>(regions_->size());
  s.last_solve_time_s = counters_.last_solve_time_s;
  s.map_age_s = regions_ == nullptr ? -1.0 : 1e-6 * static_cast<double>(now - map_receive_utime_);
  s.uptime_s = 1e-6 * static_cast<double>(now - start_utime_);
  s.superseded_requests = counters_.superseded_requests;
  s.expired_requests = counters_.expired_requests;
  s.time_limit_endings = counters_.time_limit_endings;
  s.abandoned_solves = counters_.abandoned_solves;
  s.inbox_overflows = counters_.inbox_overflows;
  s.superseded_maps = counters_.superseded_maps;
  s.empty_maps = counters_.empty_maps;
  s.publish_failures = counters_.publish_failures;
  s.internal_errors = counters_.internal_errors;
  s.udp_receive_errors = udp;
  s.extracting_map = extracting_;
  std::ostringstream msg;
  msg << (regions_ == nullptr ? "waiting for a map" : planning_ ? "planning" : "idle")
      << (extracting_ ? ", extracting a map" : "") << "; requests " << s.requests << ", plans "
      << s.plans << ", rejected messages " << s.rejected_messages << ", invalid "
      << s.invalid_requests << ", dropped " << s.dropped_requests << ", superseded "
      << s.superseded_requests << ", expired " << s.expired_requests << ", time limit "
      << s.time_limit_endings << ", intake overflows " << s.inbox_overflows
      << ", publish failures " << s.publish_failures << ", internal errors "
      << counters_.internal_errors;
  s.message = msg.str();
  return s;
}

void DaemonCore::PublishStatus() { Publish(kStatusChannel, StatusMessage()); }

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
  return counters_;
}

size_t DaemonCore::queue_length() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

}  // namespace mfp
