// DaemonCore's planning: take the newest queued request, plan it on a task the core can
// stop waiting for by the request's deadline, answer it and record the outcome.
#include "daemon/daemon_core.h"

#include <atomic>
#include <sstream>

#include "base/check.h"
#include "base/deadline.h"
#include "daemon/abandonable_task.h"
#include "daemon/heap_release.h"
#include "daemon/message_conversion.h"

namespace mfp {
namespace {

std::string Seconds(double s) {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << s;
  return out.str();
}

// The plan accepted so far (window by window): the watchdog's answer at the deadline.
struct PlanSoFar {
  std::mutex mutex;
  std::optional<Plan> plan;
};

}  // namespace

std::optional<DaemonCore::PlanJob> DaemonCore::TakeNextJob() {
  PlanJob job;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return std::nullopt;
    std::optional<QueuedRequest> next = queue_.PopNewest();
    if (!next) return std::nullopt;
    job.queued = std::move(*next);
    job.setup = setup_;
    job.regions = regions_;
    job.seen_surface = seen_surface_;
    job.body_obstacles = body_obstacles_;
    job.map_utime = map_utime_;
    job.map_frame = map_frame_;
    planning_ = true;
    if (job.setup->config.limits.warm_start_plans > 0) {
      // Also for a new goal: the plan's steps are then only a proposal the search weighs.
      const auto last = last_plans_.find(job.queued.robot_name);
      if (last != last_plans_.end()) job.warm_start = last->second;
    }
  }
  // The deadline counts from the request's arrival: time spent queued is spent.
  job.limit_s = job.queued.request.time_limit_s > 0 ? job.queued.request.time_limit_s
                                                    : job.setup->config.planner.default_time_limit_s;
  job.waited_s = 1e-6 * static_cast<double>(clock_() - job.queued.receive_utime);
  return job;
}

Plan DaemonCore::RunPlanner(PlanJob& job, const RobotModel& robot, bool* abandoned) {
  const double remaining_s = job.limit_s - job.waited_s;
  const double margin_s = job.setup->config.limits.reply_margin_s;
  PlanRequest request = job.queued.request;
  request.time_limit_s = remaining_s - margin_s;
  request.warm_start = std::move(job.warm_start);
  request.seen_surface = job.seen_surface;  // the map planned on, which may be newer than the validated one
  if (job.body_obstacles) request.body_obstacles = *job.body_obstacles;
  // The planner checks this flag inside its solves: set when the core stops waiting
  // (a stop, or the deadline passed), so an abandoned plan ends at its next check
  // instead of running on. The task holds the flag, so it outlives the core's wait.
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  request.deadline = Deadline::After(remaining_s - margin_s).WithStop(cancel.get());
  auto so_far = std::make_shared<PlanSoFar>();
  request.on_plan_so_far = [so_far](const Plan& p) {
    std::lock_guard<std::mutex> lock(so_far->mutex);
    so_far->plan = p;
  };
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(remaining_s));
  TaskLauncher launcher;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    launcher = launcher_;
  }
  Plan plan;
  try {
    // The task owns what it reads (setup and regions by shared pointer), so a plan left
    // running after its deadline or a stop touches nothing of the core's. No thread
    // (std::system_error) is an internal_error reply below.
    AbandonableTask<Plan> task(
        [plan_function = plan_function_, setup = job.setup, regions = job.regions, robot = &robot, request,
         cancel] { return plan_function(*robot, *regions, request, setup->config.planner); },
        plan_tasks_, launcher);
    std::optional<Plan> result = task.Wait(deadline, stopped_);
    if (result) return std::move(*result);
    cancel->store(true);
    *abandoned = true;
    if (stopped_) {
      plan.status = SolveStatus::kDropped;
      plan.message = "dropped: the daemon is stopping; the plan in progress was abandoned";
      return plan;
    }
    {
      std::lock_guard<std::mutex> lock(so_far->mutex);
      if (so_far->plan) plan = *so_far->plan;
    }
    return AnswerAtDeadline(job, std::move(plan));
  } catch (const InputError& e) {
    plan = Plan();
    plan.status = SolveStatus::kInvalidRequest;
    plan.message = e.what();
  } catch (const std::exception& e) {
    plan = Plan();
    plan.status = SolveStatus::kInternalError;
    plan.message = std::string("planner failed: ") + e.what();
  }
  return plan;
}

Plan DaemonCore::AnswerAtDeadline(const PlanJob& job, Plan so_far) {
  const std::string why = " by the deadline (" + Seconds(job.limit_s) + " s from arrival, " +
                          Seconds(job.waited_s) + " s of it queued)";
  if (so_far.footsteps.empty()) {
    so_far.status = SolveStatus::kTimeLimit;
    so_far.message = "the planner had no plan" + why;
    return so_far;
  }
  // Anytime: the windows accepted so far, each step valid. Counted as a time-limit ending.
  so_far.message = "the planner had not finished" + why + "; " + so_far.message;
  so_far.solve_time_s = 1e-6 * static_cast<double>(clock_() - job.queued.receive_utime);
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.time_limit_endings;
  return so_far;
}

void DaemonCore::RecordOutcome(const PlanJob& job, const Plan& plan, bool abandoned) {
  std::lock_guard<std::mutex> lock(mutex_);
  planning_ = false;
  counters_.last_solve_time_s = plan.solve_time_s;
  if (plan.status == SolveStatus::kInternalError) ++counters_.internal_errors;
  if (plan.status == SolveStatus::kTimeLimit) ++counters_.time_limit_endings;
  if (plan.status == SolveStatus::kDropped) ++counters_.dropped_requests;
  // The goal is checked by the planner (ValidateRequest leaves a far goal to it): an
  // input error all the same.
  if (plan.status == SolveStatus::kInvalidGoal) ++counters_.invalid_requests;
  if (abandoned) ++counters_.abandoned_solves;
  // Only a plan on the map still current: a map that arrived meanwhile cleared the rest.
  const int keep = job.setup->config.limits.warm_start_plans;
  if (HasPlan(plan.status) && job.regions == regions_ && keep > 0) {
    std::vector<std::vector<Footstep>>& plans = last_plans_[job.queued.robot_name];
    plans.insert(plans.begin(), plan.footsteps);
    plans.resize(std::min(plans.size(), static_cast<size_t>(keep)));
  }
}

std::optional<Plan> DaemonCore::RefuseJob(const PlanJob& job) {
  Plan plan;
  const DaemonLimits& limits = job.setup->config.limits;
  const int abandoned_running = plan_tasks_->load();  // none is being waited for now
  if (job.limit_s - job.waited_s <= limits.reply_margin_s) {
    plan.status = SolveStatus::kTimeLimit;
    plan.message = "deadline passed in the queue: waited " + Seconds(job.waited_s) + " s of its " +
                   Seconds(job.limit_s) + " s time limit";
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.expired_requests;
  } else if (job.setup->robots.count(job.queued.robot_name) == 0) {
    // The robot went away with a config reload after the request was queued.
    plan.status = SolveStatus::kInvalidRequest;
    plan.message = "robot: '" + job.queued.robot_name + "' is no longer configured";
  } else if (abandoned_running >= limits.max_abandoned_plans) {
    // Planning now could leave one more abandoned plan than allowed.
    plan.status = SolveStatus::kDropped;
    plan.message = "dropped: " + std::to_string(abandoned_running) +
                   " plans answered at their deadline are still stopping (limits.max_abandoned_plans: " +
                   std::to_string(limits.max_abandoned_plans) + "); no new planning thread until one ends";
  } else {
    return std::nullopt;
  }
  return plan;
}

// A plan that stands on footholds of the seen floor (Plan::footholds, ids above the map's
// regions) is preceded by the map's region set with the footholds added, on MFP_REGIONS and
// with the same map_utime, so every footstep_t.region_id of the reply names a published region.
void DaemonCore::PublishFootholds(const PlanJob& job, const Plan& plan) {
  if (plan.footholds.empty() || job.regions == nullptr) return;
  std::vector<ConvexRegion> with_footholds = *job.regions;
  with_footholds.insert(with_footholds.end(), plan.footholds.begin(), plan.footholds.end());
  Publish(kRegionsChannel, ToRegionSetMessage(with_footholds, job.map_frame, clock_(), job.map_utime));
}

bool DaemonCore::PlanNext() {
  std::optional<PlanJob> job = TakeNextJob();
  if (!job) return false;
  const QueuedRequest& next = job->queued;
  bool abandoned = false;
  std::optional<Plan> refused = RefuseJob(*job);
  const Plan plan = refused ? std::move(*refused)
                            : RunPlanner(*job, job->setup->robots.at(next.robot_name), &abandoned);
  RecordOutcome(*job, plan, abandoned);
  Log("request " + std::to_string(next.request_id) + " planned: " + ToString(plan.status) + ", " +
      std::to_string(plan.footsteps.size()) + " footsteps, " + Seconds(plan.solve_time_s) + " s" +
      (plan.message.empty() ? "" : " (" + plan.message + ")"));
  PublishFootholds(*job, plan);
  Reply(ToPlanMessage(plan, next.request_id, next.robot_name, clock_(), job->map_utime));
  // After the reply: each plan runs on a thread of its own, whose arena keeps what the
  // plan freed (on the 577-region soak field tens of MiB, growing for minutes).
  ReleaseFreeHeap();
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
}  // namespace mfp
