#include "planner/formulation/step_limits.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/check.h"

namespace mfp {

void AddStepLimits(StepEncoder& e, const RobotModel& robot, int i) {
  const int n = e.num_legs();
  for (int axis = 0; axis < 2; ++axis) {
    const char* ax = axis == 0 ? "x" : "y";
    e.AddRow(RowKind::kReferenceBox, std::string("ref_") + ax + "_" + std::to_string(i),
             e.Position(i, axis) - e.NominalFoot(i, axis), -robot.l_bnd_m, robot.l_bnd_m);
    e.AddRow(RowKind::kReachability, std::string("reach_") + ax + "_" + std::to_string(i),
             e.Position(i, axis) - e.NominalFoot(i - n, axis), -robot.d_lim_m, robot.d_lim_m);
  }
  if (robot.reach_shape == ReachShape::kOctagon) {
    // The octagon's diagonal rows, scaled to metres along the diagonal: |dx +- dy| / sqrt(2) <= d_lim.
    const double s = 1.0 / std::sqrt(2.0);
    const StepExpr dx = e.Position(i, 0) - e.NominalFoot(i - n, 0);
    const StepExpr dy = e.Position(i, 1) - e.NominalFoot(i - n, 1);
    e.AddRow(RowKind::kReachability, StepName("reach_xpy", i), FoldRotations(s * (dx + dy)), -robot.d_lim_m,
             robot.d_lim_m);
    e.AddRow(RowKind::kReachability, StepName("reach_xmy", i), FoldRotations(s * (dx - dy)), -robot.d_lim_m,
             robot.d_lim_m);
  }
  e.AddRow(RowKind::kHeightChange, StepName("dz", i), e.Position(i, 2) - e.Position(i - n, 2), -robot.dz_max_m,
           robot.dz_max_m);
}

std::vector<double> MaxMovesXY(const StepExpressions& e, const RobotModel& robot, int num_steps) {
  const int n = e.num_legs();
  auto constant = [](const LinExpr& x) {
    MFP_CHECK(x.terms.empty());
    return x.constant;
  };
  // How far each start foot is from its own nominal position (infinity norm).
  std::vector<double> start_offset(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      start_offset[i] = std::max(start_offset[i], std::abs(constant(e.Position(i, axis)) - constant(e.NominalFoot(i, axis))));
    }
  }
  std::vector<double> moves(num_steps, 0.0);
  for (int i = n; i < num_steps; ++i) moves[i] = robot.d_lim_m + (i - n < n ? start_offset[i - n] : robot.l_bnd_m);
  return moves;
}

}  // namespace mfp
