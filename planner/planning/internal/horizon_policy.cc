#include "planner/planning/internal/horizon_policy.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "planner/planning/internal/plan_progress.h"

namespace mfp {
namespace {

// Retries of one plan's windows (longer, closer and clear-of-body re-plans together): a
// bound on the work a plan that cannot progress spends before it ends.
constexpr int kMaxHorizonRetries = 50;
// The closest local goal a re-plan after a body clash aims at, as a fraction of the
// default lookahead (three halvings).
constexpr double kMinLookaheadScale = 0.125;

}  // namespace

HorizonPolicy::HorizonPolicy(const PlanContext& context)
    : context_(context),
      horizon_(context.window_steps),
      max_horizon_(context.guided ? std::min(1000, context.options.max_horizon_windows * context.window_steps)
                                  : context.window_steps) {}

int HorizonPolicy::NextWindowSteps(const HorizonState& state) const {
  return std::min(horizon_, context_.max_steps - state.planned);
}

bool HorizonPolicy::RetryLonger(const std::string& why, HorizonState* state, bool proven_infeasible) {
  Plan& plan = state->plan;
  if (context_.TimeLeftSeconds() <= 0.0 || plan.horizon_retries >= kMaxHorizonRetries) return false;
  if (horizon_ >= max_horizon_) {
    // Proven infeasible at the longest look: the steps before it led into the dead end.
    // Plan again from the start of the window before, at the longest look.
    if (!proven_infeasible || max_horizon_ <= context_.window_steps || state->snapshots.size() < 2 ||
        earlier_retries_ >= context_.options.max_windows_without_progress) {
      return false;
    }
    last_failure_ = std::max(last_failure_, state->planned);
    state->BackUp(/*past_failed_window=*/true);
    ++earlier_retries_;
    ++plan.horizon_retries;
    plan.message = why;
    return true;
  }
  const bool new_failure = state->planned > last_failure_;
  last_failure_ = std::max(last_failure_, state->planned);
  state->BackUp(/*past_failed_window=*/new_failure);
  horizon_ = std::min(max_horizon_, 2 * horizon_);
  ++plan.horizon_retries;
  plan.message = why;
  return true;
}

std::optional<std::string> HorizonPolicy::Stuck(const HorizonState& state, int kept) const {
  if (state.plan.reaches_goal) return std::nullopt;
  if (kept == 0) return state.WindowName() + " found no step that improves on standing still";
  if (!context_.guided || state.snapshots.size() < 2) return std::nullopt;
  const int n = context_.robot.num_legs();
  const std::vector<Eigen::Vector3d> now = state.FeetAfter(state.plan.footsteps.size());
  double moved = 0.0;
  for (size_t back = 1; back <= 2; ++back) {
    const std::vector<Eigen::Vector3d> before = state.FeetAfter(state.snapshots[state.snapshots.size() - back].footsteps);
    for (int leg = 0; leg < n; ++leg) moved = std::max(moved, (now[leg] - before[leg]).norm());
  }
  const double d_lim = context_.robot.d_lim_m;
  if (!(moved < 0.1 * d_lim)) return std::nullopt;
  return state.WindowName() + " only shuffled the feet (none moved " + std::to_string(0.1 * d_lim) +
         " m in two windows)";
}

std::optional<std::string> HorizonPolicy::Stalled(const HorizonState& state) const {
  const int limit = context_.options.max_windows_without_progress;
  if (limit <= 0 || state.plan.reaches_goal || state.windows_without_progress < limit) return std::nullopt;
  std::ostringstream why;
  why.precision(3);
  why << "no progress in " << state.windows_without_progress << " windows (the way left did not shrink by "
      << MinProgressGain(context_) << " m; best: " << state.best_remaining_m << " m left after window "
      << state.best_window << ")";
  return why.str();
}

bool HorizonPolicy::CanReplanCloser(const HorizonState& state, int retries_after) const {
  return lookahead_scale_ > kMinLookaheadScale && context_.TimeLeftSeconds() > 0.0 &&
         state.plan.horizon_retries + retries_after < kMaxHorizonRetries;
}

bool HorizonPolicy::ReplanCloser(const std::string& why, HorizonState* state) {
  if (!CanReplanCloser(*state, 0)) return false;
  lookahead_scale_ *= 0.5;
  state->BackUp(/*past_failed_window=*/false);
  ++state->plan.horizon_retries;
  state->plan.message = why;
  return true;
}

bool HorizonPolicy::RetryClearOfBody(const std::string& why, HorizonState* state) {
  // Only while a closer re-plan can still follow it: a retry without a plan goes on to one.
  if (!CanReplanCloser(*state, 1)) return false;
  state->BackUp(/*past_failed_window=*/false);
  ++state->plan.horizon_retries;
  state->plan.message = why;
  return true;
}

bool HorizonPolicy::FinishAtGoal(HorizonState* state) {
  if (finishing_ || state->plan.reaches_goal || context_.TimeLeftSeconds() <= 0.0) return false;
  if (!(RemainingWay(context_, state->plan.footsteps) <= context_.robot.d_lim_m)) return false;
  finishing_ = true;
  state->windows_without_progress = 0;
  return true;
}

void HorizonPolicy::OnStepsKept(HorizonState* state, int kept) {
  lookahead_scale_ = 1.0;
  if (state->windows_without_progress == 0) earlier_retries_ = 0;
  if (kept == 0) return;
  if (state->planned > last_failure_) horizon_ = context_.window_steps;  // past the dead end
  state->plan.message.clear();
}

}  // namespace mfp
