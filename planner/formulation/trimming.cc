#include "planner/formulation/internal/trimming.h"

#include <string>

namespace mfp {

void AddTrimming(const StepExpressions& e, const RobotModel& robot, const std::vector<double>& max_move_xy,
                 int num_steps, bool monotone, MiqpBuilder* b, FootstepVariables* vars) {
  const int n = e.num_legs();
  vars->trim.assign(num_steps, -1);
  for (int i = n; i < num_steps; ++i) {
    const int t = b->AddBinary(StepName("trim", i));
    vars->trim[i] = t;
    for (int axis = 0; axis < 3; ++axis) {
      const double M = axis < 2 ? max_move_xy[i] : robot.dz_max_m;
      const LinExpr move = e.Position(i, axis) - e.Position(i - n, axis);
      const std::string tag = std::string(axis == 0 ? "x" : axis == 1 ? "y" : "z") + "_" + std::to_string(i);
      b->AddRow("trim_up_" + tag, move + LinExpr::Var(t, M), -kInfinity, M);
      b->AddRow("trim_dn_" + tag, move - LinExpr::Var(t, M), -M, kInfinity);
    }
    if (monotone && i > n) {
      b->AddRow(StepName("trim_suffix", i), LinExpr::Var(vars->trim[i - 1]) - LinExpr::Var(t), -kInfinity, 0.0);
    }
  }
}

void AddTrimmedConfigurationsHoldYaw(const StepExpressions& e, const RobotModel& robot, int num_configurations,
                                     const FootstepVariables& vars, MiqpBuilder* b) {
  const int n = e.num_legs();
  const double M = robot.max_yaw_change_rad;
  for (int cfg = 1; cfg < num_configurations; ++cfg) {
    const int t = vars.trim[static_cast<size_t>(cfg * n)];
    if (t < 0) continue;
    const LinExpr turn = e.Yaw(cfg) - e.Yaw(cfg - 1);
    b->AddRow(StepName("hold_yaw_up", cfg), turn + LinExpr::Var(t, M), -kInfinity, M);
    b->AddRow(StepName("hold_yaw_dn", cfg), turn - LinExpr::Var(t, M), -M, kInfinity);
  }
}

}  // namespace mfp
