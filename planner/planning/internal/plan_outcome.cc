#include "planner/planning/internal/plan_outcome.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "planner/planning/internal/goal.h"
#include "planner/planning/internal/stop_report.h"

namespace mfp {
namespace {

double RelativeGap(const Plan& plan) {
  return (plan.objective - plan.bound) / std::max(1.0, std::abs(plan.objective));
}

}  // namespace

Plan Rejected(SolveStatus status, const std::string& message) {
  Plan plan;
  plan.status = status;
  plan.message = message;
  return plan;
}

void EndOnTimeLimit(const PlanContext& context, HorizonState* state) {
  state->plan.status = SolveStatus::kTimeLimit;
  state->end_reason = "time_limit";
  std::ostringstream msg;
  msg.precision(3);
  msg << (context.request.deadline.Stopped() ? "stopped after " : "time limit reached after ") << state->planned
      << " steps (" << context.ElapsedSeconds() << " s: " << state->plan.setup_s
      << " s of set-up, the route search among them, before " << state->plan.windows << " window"
      << (state->plan.windows == 1 ? "" : "s") << ")";
  state->plan.message = msg.str();
}

void EndOnInfeasibleWindow(const std::string& reason, HorizonState* state) {
  Plan& plan = state->plan;
  plan.status = plan.windows == 1 ? SolveStatus::kInfeasible : plan.status;
  plan.message = reason;
  state->end_reason = "window_infeasible";
}

void EndOnFailedSearch(const PlanContext& context, const BranchAndBoundResult& result, HorizonState* state) {
  Plan& plan = state->plan;
  if (plan.windows == 1) {
    plan.status = result.status;
  } else {
    plan.status = context.guided                              ? plan.status
                  : result.status == SolveStatus::kInfeasible ? plan.status
                                                              : result.status;
    // Unguided, a later window cut by its time share before its first plan: the plan
    // so far stands, ended by the time limit.
    if (!context.guided && result.status == SolveStatus::kNoSolution) plan.status = SolveStatus::kTimeLimit;
  }
  plan.message = state->WindowName() + ": " + ToString(result.status) + " after " + std::to_string(result.nodes) +
                 " nodes";
  // Without a plan, whether the root relaxation was solved: out of time before it, a
  // window has nothing to round; after it, its roundings and dives (which may run past the
  // window's deadline by polish.completion_overrun_s) found no plan in time.
  if (result.status == SolveStatus::kNoSolution) {
    plan.message += std::isfinite(result.root_bound)
                        ? ": its root relaxation was solved, but its roundings and dives found no plan within its limits"
                        : ": " + std::string(context.request.deadline.Stopped() ? "stopped" : "out of time") +
                              " before its root relaxation was solved";
  }
  state->end_reason = "window_failed";
}

void EndOnInexactWindow(const ExactWindow& exact, HorizonState* state) {
  Plan& plan = state->plan;
  if (plan.windows == 1) plan.status = SolveStatus::kNoSolution;
  plan.message = state->WindowName() + ": the polisher could not make it exact (" + exact.polished.report.message +
                 "), " + exact.replan.note;
  state->end_reason = "window_inexact";
}

void EndStuck(const std::string& why, HorizonState* state) {
  state->plan.message = "the planner stopped short of the goal: " + why;
  state->end_reason = "stuck";
}

void EndStalled(const std::string& why, HorizonState* state) {
  state->plan.message = "the plan stopped making progress: " + why;
  state->end_reason = "no_progress";
}

void ReportWindow(const PlanContext& context, const HorizonState& state, int kept, const ExactWindow& exact,
                  const std::function<void(const PlanProgress&)>& on_progress) {
  const Plan& plan = state.plan;
  if (context.request.on_plan_so_far && kept > 0) {
    Plan so_far = plan;
    so_far.status = plan.reaches_goal ? plan.status : SolveStatus::kPartial;
    so_far.message = "the plan so far: " + std::to_string(state.planned) + " steps";
    so_far.gap = RelativeGap(plan);
    so_far.solve_time_s = context.ElapsedSeconds();
    context.request.on_plan_so_far(so_far);
  }
  if (on_progress) {
    PlanProgress progress;
    progress.window = plan.windows;
    progress.steps_planned = state.planned;
    progress.distance_to_goal_m = (StanceCentreXY(state.stance) - context.GoalXY()).norm();
    progress.elapsed_s = context.ElapsedSeconds();
    progress.window_result = exact.result;
    progress.polish = exact.polished.report;
    progress.record = plan.window_records.back();
    on_progress(progress);
  }
}

namespace {

// What keeps a stopped plan's last stance from the goal, in the goal test's own terms (the
// centre's distance alone can be far inside the tolerance while a foot or the yaw is not).
std::string GoalMiss(const PlanContext& context, const std::vector<Footstep>& footsteps) {
  if (footsteps.size() < static_cast<size_t>(context.robot.num_legs())) return "";
  const GoalDistances d = DistancesToGoal(context.robot, footsteps, context.goal);
  const double farthest_foot_m = d.foot_m.empty() ? 0.0 : *std::max_element(d.foot_m.begin(), d.foot_m.end());
  std::ostringstream msg;
  msg.precision(3);
  msg << " (farthest foot " << farthest_foot_m << " m from its goal spot, goal_tolerance " << context.goal.tolerance_m
      << " m; yaw " << d.yaw_rad << " rad off, goal_yaw_tolerance " << context.goal.yaw_tolerance_rad << " rad)";
  return msg.str();
}

// For a plan that stopped making progress, got stuck or ended on a failed window: when its
// last windows' searches all ended by their time shares, that is part of why, and the note
// says so.
std::string TimeShareNote(const Plan& plan, const std::string& end_reason) {
  if (end_reason != "no_progress" && end_reason != "stuck" && end_reason != "window_failed") return "";
  int cut = 0;
  double least_s = 0.0, most_s = 0.0;
  for (auto w = plan.window_records.rbegin(); w != plan.window_records.rend(); ++w) {
    if (w->status != SolveStatus::kTimeLimit && w->status != SolveStatus::kNoSolution) break;
    least_s = cut == 0 ? w->time_limit_s : std::min(least_s, w->time_limit_s);
    most_s = cut == 0 ? w->time_limit_s : std::max(most_s, w->time_limit_s);
    ++cut;
  }
  if (cut == 0) return "";
  std::ostringstream note;
  note.precision(2);
  note << "; the last " << (cut == 1 ? "window's search ended by its time share" : std::to_string(cut) +
                                        " windows' searches ended by their time shares")
       << " (" << least_s;
  if (most_s > least_s) note << "-" << most_s;
  note << " s)";
  return note.str();
}

}  // namespace

Plan FinishPlan(const PlanContext& context, HorizonState* state) {
  Plan& plan = state->plan;
  const PlanRequest& request = context.request;
  if (!plan.reaches_goal && plan.message.empty() && HasPlan(plan.status)) {
    plan.message = state->planned < context.max_steps && request.max_windows > 0
                       ? "goal not reached within " + std::to_string(request.max_windows) + " window(s)"
                       : "goal not reached within " + std::to_string(context.max_steps) + " steps";
  }
  if (!state->polish_note.empty()) plan.message += (plan.message.empty() ? "" : "; ") + state->polish_note;
  if (!plan.reaches_goal && HasPlan(plan.status) && request.max_windows == 0) {
    // Every accepted step satisfies the constraints: the robot can walk this far safely.
    // Steps past the plan's best point only marked time (or a retry backed up behind it).
    if (state->ReturnToBest()) {
      plan.message += "; kept the steps up to window " + std::to_string(state->best_window) + ", its best point";
    }
    const Eigen::Vector2d centre = StanceCentreXY(state->stance);
    // The report finishes what an expired plan began: bounded past the plan's deadline by
    // the completion overrun, as a window's completion is.
    const Deadline report = context.request.deadline.Within(context.TimeLeftSeconds())
                                .ExtendedBy(context.options.polish.completion_overrun_s);
    plan.stop = DescribeStop(context, plan, state->end_reason.empty() ? "step_budget" : state->end_reason, report);
    std::ostringstream msg;
    msg.precision(3);
    msg << "partial plan: " << state->planned << " steps, stopped " << (centre - context.GoalXY()).norm()
        << " m from the goal" << GoalMiss(context, plan.footsteps) << ": " << plan.message
        << TimeShareNote(state->plan, state->end_reason) << "; " << StopText(context.robot, plan.stop);
    plan.message = msg.str();
    plan.status = SolveStatus::kPartial;
  }
  plan.gap = RelativeGap(plan);
  plan.solve_time_s = context.ElapsedSeconds();
  return std::move(plan);
}

}  // namespace mfp
