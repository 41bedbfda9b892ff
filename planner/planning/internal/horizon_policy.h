#pragma once
// The horizon's policy for retries, stalls and longer looks (adaptive horizons): a window
// that is infeasible, finds no plan in its time, cannot be made exact, or cannot improve
// on standing still (or only shuffles the feet) is planned again from the stance before
// the previous window with a longer horizon (doubling up to max_horizon_windows default
// windows, only under route guidance), so that the steps that led into a dead end can
// change. A window that keeps steps past the dead end resets the horizon. A window proven
// infeasible at the longest look is still planned again from the start of the window
// before (at most max_windows_without_progress times between two gains). A plan whose way
// left has not shrunk over max_windows_without_progress accepted windows has stalled.
// Private to planner/planning.
#include <optional>
#include <string>

#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"

namespace mfp {

class HorizonPolicy {
 public:
  explicit HorizonPolicy(const PlanContext& context);

  // New footsteps of the next window: the horizon, at most the steps left.
  int NextWindowSteps(const HorizonState& state) const;
  // On a failed window: true when it is worth planning again with a longer look; then
  // the state is backed up, the horizon doubled, the retry counted and `why` made the
  // plan's message. False (nothing changed) when the horizon is at its longest, the
  // plan's time is up, or 50 retries were spent. proven_infeasible: the window has no
  // plan at all (not one cut by its time); at the longest look it is still planned again
  // from an earlier point (above).
  bool RetryLonger(const std::string& why, HorizonState* state, bool proven_infeasible = false);
  // Why the plan has stalled short of the goal: its way left did not shrink over the last
  // max_windows_without_progress accepted windows (HorizonState::NoteProgress); nullopt
  // while it progresses, or when the rule is off (0).
  std::optional<std::string> Stalled(const HorizonState& state) const;
  // Why a window that was accepted leaves the horizon stuck short of the goal: it kept
  // no step, or (guided) its steps only shuffle the feet, none moving a tenth of d_lim
  // from where it stood one and two windows ago, which the next windows would repeat
  // until the step budget ends. nullopt when it made progress or reached the goal.
  std::optional<std::string> Stuck(const HorizonState& state, int kept) const;
  // The window's plan takes the body into an obstacle between the route's poses (why):
  // true when it is worth planning it again from its own start with the local goal at
  // half the lookahead (closer to the route, whose poses are clear); then the state is
  // backed up and the retry counted. False at an eighth of the lookahead or when the
  // plan's time is up.
  bool ReplanCloser(const std::string& why, HorizonState* state);
  // The same: true when it is worth planning it again from its own start, at the same
  // lookahead, with body regions in its MIQP (formulation.body_regions for this window);
  // then the state is backed up and the retry counted. False when ReplanCloser would
  // refuse (an eighth of the lookahead: a retry without a plan must still have a closer
  // re-plan to go to), the plan's time is up or the retry would leave none for that re-plan.
  bool RetryClearOfBody(const std::string& why, HorizonState* state);
  // A plan that stalled or is stuck within one step (d_lim) of the goal but outside its
  // tolerances: with the robot's weights a window's goal term can be worth less than the
  // trim reward of the steps that would close it (a last foot e off its spot, k steps to
  // it in the gait: goal_position e^2 < k |trim_step|, e < 6.3 cm for four legs and the
  // default weights), and each window stands still. True (once per plan) when the
  // windows from here on finish at the goal (FinishGoalWeights) and the stall count
  // starts again; false when not near, already finishing, or out of time.
  bool FinishAtGoal(HorizonState* state);
  bool finishing() const { return finishing_; }
  // The lookahead of the next window's local goal, as a fraction of the default.
  double LookaheadScale() const { return lookahead_scale_; }
  // A window kept steps: past the last failure the horizon is back to short windows,
  // and a retry's reason, now overcome, leaves the plan's message.
  void OnStepsKept(HorizonState* state, int kept);

 private:
  const PlanContext& context_;
  int horizon_ = 0;        // new footsteps of the next window
  int max_horizon_ = 0;
  int last_failure_ = -1;  // steps planned where a window last failed
  int earlier_retries_ = 0;
  bool finishing_ = false;
  double lookahead_scale_ = 1.0;  // infeasible windows retried at the longest look since the last gain

  // A closer re-plan is still possible after retries_after more retries.
  bool CanReplanCloser(const HorizonState& state, int retries_after) const;
};

}  // namespace mfp
