#pragma once
// What a window's re-certification keeps of its plan: the goal. The window's objective
// rewards the goal without demanding it (a foot a few centimetres off its spot costs less
// than the trim reward of the steps that would close the gap), so re-certification, which
// re-opens subtrees of lower objective (BranchAndBoundOptions::recertify_within), could
// trade a window plan that reaches the goal for one that stops short of it. Once the
// incumbent reaches the goal, the search is restricted to final feet within the goal's
// tolerance and to the steps the incumbent takes: a plan of fewer steps that reaches the
// goal on the MIQP's chords earns their trim reward, and its exact steps, polished, can
// end short (new_college seed 27: 7-10 cm; docs/measurements.md, stop 38). Private to
// planner/planning.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/goal.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

// Ranges of the final stance's new feet (x and y of the window's last n steps) within
// which each foot stays within goal.tolerance_m of its goal spot and the plan x stays:
// per foot the box about its spot inside the tolerance's disc that holds the foot with
// the largest area (half sides tolerance / sqrt 2 each, or, for a foot farther than that
// on one axis, its offset on that axis and the rest of the disc on the other). Empty when
// x does not reach the goal (a final foot, new or of the start stance, beyond the
// tolerance) or the window's goal is not `goal` (a local goal along the route). Then,
// for each new step x takes (trim below one half), its trim variable held at 0.
std::vector<VariableRange> GoalKeepingRanges(const MiqpFormulation& formulation, const GoalSpec& goal,
                                             const Eigen::VectorXd& x);

// GoalKeepingRanges as a search option (BranchAndBoundOptions::recertify_within) for a
// window of `formulation` (which the function refers to); nullptr when the window's goal
// is a local goal.
std::function<std::vector<VariableRange>(const Eigen::VectorXd&)> GoalKeeping(const MiqpFormulation& formulation,
                                                                              const GoalSpec& goal);

}  // namespace mfp
