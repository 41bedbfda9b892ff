#include "planner/planning/internal/horizon_state.h"

#include <algorithm>

#include "geometry/convex_region.h"
#include "planner/planning/internal/goal.h"
#include "planner/planning/internal/plan_progress.h"

namespace mfp {
namespace {

// Worst (least certain) of two window statuses that both carry a plan.
SolveStatus Combine(SolveStatus a, SolveStatus b) {
  auto rank = [](SolveStatus s) {
    return s == SolveStatus::kOptimal ? 0 : s == SolveStatus::kFeasible ? 1 : 2;
  };
  return rank(a) >= rank(b) ? a : b;
}

}  // namespace

HorizonState::HorizonState(const PlanContext& c)
    : context(c),
      stance(c.robot.num_legs()),
      history(c.robot.num_legs()),
      stance_yaw(c.robot.num_legs(), c.request.start_yaw_rad),
      yaw(c.request.start_yaw_rad) {
  const int n = c.robot.num_legs();
  plan.status = SolveStatus::kOptimal;
  for (int i = 0; i < n; ++i) {
    const int leg = c.robot.gait[i];
    stance[i] = c.request.start_feet_world_m[leg];
    Footstep f;
    f.index = i;
    f.leg = leg;
    f.position_world_m = stance[i];
    f.yaw_rad = c.request.start_yaw_rad;
    const int r = FindRegionBelow(c.regions, stance[i].x(), stance[i].y(), c.options.start_tolerance_m);
    f.region_id = r >= 0 ? c.regions[r].id : -1;
    plan.footsteps.push_back(f);
  }
  history = stance;
  UpdateGoalReached();
  start_progress_m = c.guided ? RouteProgress(c.guide, StanceCentreXY(stance)) : 0.0;
  best = Here();
  best_footsteps = plan.footsteps;
  best_remaining_m = gain_anchor_m = RemainingWay(c, plan.footsteps);
}

bool HorizonState::WantsAnotherWindow() const {
  // A step budget one window holds is one MIQP (DESIGN.md: `--window N --max-steps N`):
  // once that window has kept steps, the steps it trimmed are not planned by another.
  const bool budget_was_one_window = context.window_steps >= context.max_steps && planned > 0;
  return !plan.reaches_goal && planned < context.max_steps && !budget_was_one_window &&
         (context.request.max_windows <= 0 || plan.windows < context.request.max_windows);
}

void HorizonState::BackUp(bool past_failed_window) {
  if (past_failed_window && snapshots.size() >= 2) {
    snapshots.pop_back();  // the failed window's own start
    Restore(snapshots.back());
    snapshots.pop_back();
  } else if (!snapshots.empty()) {
    Restore(snapshots.back());
    snapshots.pop_back();
  }
}

void HorizonState::CountWindow(const MiqpFormulation& formulation) {
  if (plan.windows == 0) {
    plan.integer_variables = formulation.miqp().num_integer();
    plan.objective_offset = formulation.miqp().constant;
  }
  ++plan.windows;
}

void HorizonState::RecordWindow(const WindowRecord& record) {
  plan.window_records.push_back(record);
  plan.nodes += record.nodes;
  plan.relaxations += record.relaxations;
  plan.relaxation_fallbacks += record.fallbacks;
}

int HorizonState::Accept(const MiqpFormulation& used, const BranchAndBoundResult& result,
                         const std::vector<Footstep>& steps) {
  const int n = context.robot.num_legs();
  plan.status = Combine(plan.status, result.status);
  plan.objective += result.objective;
  plan.bound += result.bound;
  const int kept = KeptSteps(used, result);
  for (int i = n; i < n + kept; ++i) {
    Footstep f = steps[i];
    f.index = static_cast<int>(plan.footsteps.size());
    plan.footsteps.push_back(f);
  }
  planned += kept;
  if (kept > 0) ++accepted_windows;
  plan.window_records.back().kept_steps = kept;
  phase = (phase + kept) % n;
  const int size = static_cast<int>(plan.footsteps.size());
  for (int i = 0; i < n; ++i) {
    stance[i] = plan.footsteps[size - n + i].position_world_m;
    stance_yaw[i] = plan.footsteps[size - n + i].yaw_rad;
    // Before the plan started the robot stood in its start stance.
    const int before = size - 2 * n + i;
    history[i] = plan.footsteps[before >= 0 ? before : before + n].position_world_m;
  }
  yaw = plan.footsteps.back().yaw_rad;
  UpdateGoalReached();
  return kept;
}

void HorizonState::NoteProgress(double remaining_m, double min_gain_m) {
  if (remaining_m < best_remaining_m) {
    best = Here();
    best_footsteps = plan.footsteps;
    best_remaining_m = remaining_m;
    best_window = plan.windows;
  }
  if (remaining_m <= gain_anchor_m - min_gain_m) {
    gain_anchor_m = remaining_m;
    windows_without_progress = 0;
  } else {
    ++windows_without_progress;
  }
}

bool HorizonState::ReturnToBest() {
  if (plan.footsteps.size() == best_footsteps.size() &&
      std::equal(plan.footsteps.begin(), plan.footsteps.end(), best_footsteps.begin(),
                 [](const Footstep& a, const Footstep& b) { return a.position_world_m == b.position_world_m; })) {
    return false;
  }
  plan.footsteps = best_footsteps;
  Restore(best);
  return true;
}

int HorizonState::KeptSteps(const MiqpFormulation& used, const BranchAndBoundResult& result) const {
  const int n = context.robot.num_legs();
  int kept = 0;
  for (int i = n; i < used.num_steps(); ++i) {
    if (result.x(used.vars().trim[i]) < 0.5) kept = i - n + 1;
  }
  return kept;
}

std::vector<Eigen::Vector3d> HorizonState::FeetAfter(size_t count) const {
  const size_t n = static_cast<size_t>(context.robot.num_legs());
  std::vector<Eigen::Vector3d> feet(n);
  for (size_t k = count - n; k < count; ++k) feet[plan.footsteps[k].leg] = plan.footsteps[k].position_world_m;
  return feet;
}

void HorizonState::Restore(const Snapshot& s) {
  stance = s.stance;
  history = s.history;
  stance_yaw = s.stance_yaw;
  phase = s.phase;
  planned = s.planned;
  yaw = s.yaw;
  plan.objective = s.objective;
  plan.bound = s.bound;
  plan.footsteps.resize(s.footsteps);
  UpdateGoalReached();
}

void HorizonState::UpdateGoalReached() {
  plan.reaches_goal = WithinGoal(DistancesToGoal(context.robot, plan.footsteps, context.goal), context.goal);
}

}  // namespace mfp
