#pragma once
// A window the polisher could not make exact, planned again so that it is.
//
// The MIQP meets the reference and reachability boxes with chords of sin and cos; the
// polisher (window_polisher.h) then moves the footsteps and yaws onto the exact
// constraints, which can fail for some integer assignments (a region corner where the
// exact boxes leave no room). The re-plan solves the window's MIQP again with l_bnd and
// d_lim shrunk by ChordErrorBound: every solution of that MIQP meets the true boxes with
// exact R(yaw) (a sound inner approximation), whatever the polisher then does. The
// polisher still runs on it, against the true boxes, to win back the cost of the
// shrinking.
#include <memory>
#include <string>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/goal.h"
#include "planner/planning/internal/window_polisher.h"
#include "planner/qp/relaxation_solver.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

struct ExactReplan {
  bool planned = false;                          // a plan of the shrunk MIQP, exact
  std::unique_ptr<RobotModel> robot;             // the robot with shrunk boxes (the formulation points to it)
  std::unique_ptr<MiqpFormulation> formulation;  // the shrunk MIQP (same steps, configurations and regions)
  BranchAndBoundResult result;                   // its search's result
  PolishedWindow polished;                       // the footsteps to use (exact) and the polisher's account
  double shrink_m = 0.0;                         // how much l_bnd and d_lim were shrunk by
  std::string note;                              // what happened, for the plan's message
};

// bnb: the window's search options (time limit, deadline); polish: the polisher's.
// window_x (optional): the window's plan, a point of formulation.miqp(). When the search
// ends without a plan on bnb.deadline (typically: the window's own search took all the
// plan's time, so this one gets none), its integer assignment completed on the shrunk
// MIQP is the plan: one
// fixed-integer QP, solved past the deadline by at most polish.completion_overrun_s
// (bnb.deadline's stop flag still ends it), which keeps a window that had a plan from
// ending with none. keep_goal (optional): the plan's goal, which the re-plan's
// re-certification keeps once its plan reaches it (goal_keeping.h); bnb.recertify_within
// belongs to the window's own formulation and is replaced.
ExactReplan ReplanWithinChordError(const MiqpFormulation& formulation, const std::vector<RelaxationSolver*>& solvers,
                                   const BranchAndBoundOptions& bnb, const PolishOptions& polish,
                                   const Eigen::VectorXd* window_x = nullptr, const GoalSpec* keep_goal = nullptr);

}  // namespace mfp
