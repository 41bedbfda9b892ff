#include "planner/formulation/step_limits.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/check.h"

namespace mfp {

namespace {

// "reach_xpy" / "reach_xmy" on the diagonals, else the normal's angle in whole degrees
// ("reach_p22", "reach_m67").
std::string ReachFaceName(int k, int sides, double sign) {
  if (8 * k == sides) return sign > 0 ? "reach_xpy" : "reach_xmy";
  return std::string("reach_") + (sign > 0 ? "p" : "m") + std::to_string(360 * k / sides);
}

// The regular polygon's faces other than the axes', in metres along their normals at
// +-2 pi k / sides from x: |cos(phi) dx + sin(phi) dy| <= d_lim of the move from r_nom,i-n
// (the octagon's |dx +- dy| / sqrt(2) <= d_lim).
void AddPolygonFaces(StepEncoder& e, const RobotModel& robot, int i, int sides) {
  const int n = e.num_legs();
  const StepExpr dx = e.Position(i, 0) - e.NominalFoot(i - n, 0);
  const StepExpr dy = e.Position(i, 1) - e.NominalFoot(i - n, 1);
  for (int k = 1; 4 * k < sides; ++k) {
    for (const double sign : {1.0, -1.0}) {
      StepExpr along;
      if (8 * k == sides) {
        along = (1.0 / std::sqrt(2.0)) * (dx + sign * dy);
      } else {
        const double phi = 2.0 * M_PI * k / sides;
        along = std::cos(phi) * dx + (sign * std::sin(phi)) * dy;
      }
      e.AddRow(RowKind::kReachability, StepName(ReachFaceName(k, sides, sign).c_str(), i), FoldRotations(along),
               -robot.d_lim_m, robot.d_lim_m);
    }
  }
}

}  // namespace

void AddStepLimits(StepEncoder& e, const RobotModel& robot, int i) {
  const int n = e.num_legs();
  for (int axis = 0; axis < 2; ++axis) {
    const char* ax = axis == 0 ? "x" : "y";
    e.AddRow(RowKind::kReferenceBox, std::string("ref_") + ax + "_" + std::to_string(i),
             e.Position(i, axis) - e.NominalFoot(i, axis), -robot.l_bnd_m, robot.l_bnd_m);
    e.AddRow(RowKind::kReachability, std::string("reach_") + ax + "_" + std::to_string(i),
             e.Position(i, axis) - e.NominalFoot(i - n, axis), -robot.d_lim_m, robot.d_lim_m);
  }
  const int sides = ReachShapeSides(robot.reach_shape);
  if (sides > 4) AddPolygonFaces(e, robot, i, sides);
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
