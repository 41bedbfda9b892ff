#pragma once
// The seed paper's objective:
//   goal       w_goal sum over the final stance |f_i - g_leg(i)|^2 (x, y), g the goal's
//              nominal feet; w_yaw (theta_B-1 - goal yaw)^2
//   trimming   w_trim sum_i t_i (w_trim < 0: fewer steps are better)
//   progress   w_disp sum_i |p_i - p_i-n|^2, the centre of contacts' motion between
//              configurations
#include "planner/formulation/internal/footstep_problem.h"
#include "planner/formulation/internal/step_expressions.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

// problem.goal_yaw_rad: unwrapped to within pi of the start yaw (MiqpFormulation's copy is).
void AddCost(const StepExpressions& e, const FootstepProblem& problem, int num_steps, int num_configurations,
             const FootstepVariables& vars, MiqpBuilder* b);

// Goal foot position (x, y) of a leg [m]: its nominal foot at the goal pose.
Eigen::Vector2d GoalFoot(const FootstepProblem& problem, int leg);

}  // namespace mfp
