#pragma once
// Trimming (seed paper): a binary t_i per new step; t_i => the foot stays where it was,
// f_i = f_i-n, written as |f_i - f_i-n| <= M (1 - t_i) per axis with M the step's largest
// move. With monotone trimming, trimmed steps form a suffix (t_i-1 <= t_i): once stopped,
// the robot stays stopped, which removes symmetric solutions.
#include <vector>

#include "planner/formulation/internal/footstep_problem.h"
#include "planner/formulation/internal/step_expressions.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// max_move_xy: MaxMovesXY (step_limits.h).
void AddTrimming(const StepExpressions& e, const RobotModel& robot, const std::vector<double>& max_move_xy,
                 int num_steps, bool monotone, MiqpBuilder* b, FootstepVariables* vars);

// A configuration whose first step is trimmed does not turn: t_(cfg n) => theta_cfg =
// theta_(cfg-1), written |theta_cfg - theta_(cfg-1)| <= max_yaw_change (1 - t_(cfg n)).
// With trimming as a suffix the last configuration's yaw is then the yaw of the last step
// taken: the body yaw the plan reports, the goal test checks and the goal cost weighs.
// Without it a trimmed configuration could turn to the goal yaw on paper while the steps
// the robot takes end at another yaw. Needs AddTrimming's variables.
void AddTrimmedConfigurationsHoldYaw(const StepExpressions& e, const RobotModel& robot, int num_configurations,
                                     const FootstepVariables& vars, MiqpBuilder* b);

}  // namespace mfp
