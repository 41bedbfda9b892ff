#include "planner/formulation/step_encoder.h"

namespace mfp {

StepExpr& StepExpr::operator+=(const StepExpr& other) {
  lin += other.lin;
  rotations.insert(rotations.end(), other.rotations.begin(), other.rotations.end());
  return *this;
}

StepExpr& StepExpr::operator-=(const StepExpr& other) {
  lin -= other.lin;
  for (RotatedOffset r : other.rotations) {
    r.coefficient = -r.coefficient;
    rotations.push_back(r);
  }
  return *this;
}

StepExpr& StepExpr::operator*=(double scale) {
  lin *= scale;
  for (RotatedOffset& r : rotations) r.coefficient *= scale;
  return *this;
}

StepExpr FoldRotations(StepExpr expr) {
  if (expr.rotations.size() < 2) return expr;
  const RotatedOffset& first = expr.rotations.front();
  RotatedOffset folded = first;
  folded.coefficient = -1.0;
  folded.axis = 0;
  folded.offset_body_m = Eigen::Vector2d::Zero();
  for (const RotatedOffset& r : expr.rotations) {
    if (r.yaw_var != first.yaw_var || r.fixed_yaw_rad != first.fixed_yaw_rad) return expr;
    // A_y o = R(-pi/2) o = (o_y, -o_x).
    const Eigen::Vector2d turned =
        r.axis == 0 ? r.offset_body_m : Eigen::Vector2d(r.offset_body_m.y(), -r.offset_body_m.x());
    folded.offset_body_m -= r.coefficient * turned;
  }
  expr.rotations = {folded};
  return expr;
}

}  // namespace mfp
