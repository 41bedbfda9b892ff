#pragma once
// Warm start for replanning: a robot replanning as it walks sends nearly the same request
// again and again (its feet moved along the last plan, the same goal and map). The steps
// of that last plan still ahead of the robot are a good integer assignment for the new
// window: the regions they stand in and the yaw segments of their configurations. With
// the assignment fixed the window is a convex QP, solved in a few milliseconds, and the
// search starts with that plan as its incumbent (a bound to prune against) instead of
// finding one by itself.
//
// The previous plan is only a hint: each proposal is checked against the new window's
// rows by the search like any rounding, and a plan that no longer fits (the map changed,
// the robot slipped, the goal moved) simply proposes nothing.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "base/deadline.h"
#include "planner/qp/relaxation_solver.h"

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"

namespace mfp {

struct WarmStart {
  // Every start foot lies within the match tolerance of a footstep of the previous plan:
  // the robot stands on the plan it was sent (it may have walked all of it).
  bool stance_matched = false;
  // Integer assignments for the formulation's MIQP, each a vector over all variables
  // (only integer entries are meaningful); empty when nothing of the plan is ahead.
  std::vector<Eigen::VectorXd> proposals;
};

// The warm start of formulation's MIQP from a previous plan (all its footsteps, start
// stance included, as Plan::footsteps). Each leg's start foot is matched to that leg's
// nearest footstep of the previous plan (the later one on ties); when every leg matches
// within match_tolerance_m, the new steps of each leg follow that leg's next footsteps
// of the previous plan, and past its end repeat the leg's last step (its displacement
// and yaw change), those extrapolated steps proposed trimmed too, and the last
// configuration proposed trimmed. Proposals come from MiqpFormulation::RoundAlongPlan of
// a point with the feet and yaws so placed; none when no step of the previous plan is
// ahead of the robot.
WarmStart WarmStartFrom(const MiqpFormulation& formulation, const std::vector<Footstep>& previous,
                        double match_tolerance_m);

// The best plan among the proposals that takes a step: each one's QP with its integers
// fixed, solved by solver (deadline: the caller's; these QPs take milliseconds). nullopt
// when none is feasible (rows and bounds within feasibility_tolerance) or every feasible
// one stands still (a replan that stands still is left to the full search).
std::optional<Eigen::VectorXd> SolveWarmStart(const MiqpFormulation& formulation,
                                              const std::vector<Eigen::VectorXd>& proposals,
                                              RelaxationSolver& solver, const Deadline& deadline,
                                              double feasibility_tolerance);

}  // namespace mfp
