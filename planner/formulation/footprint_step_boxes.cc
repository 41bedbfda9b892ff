#include "planner/formulation/internal/footprint_step_boxes.h"

#include <algorithm>

#include "base/check.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {
namespace {

using Box = Eigen::AlignedBox2d;

double ConstantOf(const LinExpr& x) {
  MFP_CHECK(x.terms.empty());
  return x.constant;
}

// The variable a one-term expression names (a yaw, sin or cos of a configuration).
int VariableOf(const LinExpr& x) {
  MFP_CHECK(x.terms.size() == 1 && x.terms[0].second == 1.0);
  return x.terms[0].first;
}

Box PolygonBox(const std::vector<Eigen::Vector2d>& corners, double yaw_rad) {
  Box box;
  const Eigen::Rotation2Dd turn(yaw_rad);
  for (const Eigen::Vector2d& c : corners) box.extend(turn * c);
  return box;
}

// [lo, hi] of a * u over u in [u_lo, u_hi].
Eigen::Vector2d ScaledRange(double a, double u_lo, double u_hi) {
  return Eigen::Vector2d(std::min(a * u_lo, a * u_hi), std::max(a * u_lo, a * u_hi));
}

// The box of R o = (c o_x - s o_y, s o_x + c o_y) over c in [c_lo, c_hi], s in [s_lo, s_hi].
Box RotatedOffsetBox(const Eigen::Vector2d& o, double s_lo, double s_hi, double c_lo, double c_hi) {
  const Eigen::Vector2d cx = ScaledRange(o.x(), c_lo, c_hi), sy = ScaledRange(-o.y(), s_lo, s_hi);
  const Eigen::Vector2d sx = ScaledRange(o.x(), s_lo, s_hi), cy = ScaledRange(o.y(), c_lo, c_hi);
  return Box(Eigen::Vector2d(cx(0) + sy(0), sx(0) + cy(0)), Eigen::Vector2d(cx(1) + sy(1), sx(1) + cy(1)));
}

Box Sum(const Box& a, const Box& b) { return Box(a.min() + b.min(), a.max() + b.max()); }

}  // namespace

std::vector<Box> FootprintStepBoxes(const StepExpressions& e, const MiqpBuilder& b, const RobotModel& robot,
                                    int num_steps) {
  MFP_CHECK(robot.reach_shape == ReachShape::kFootprint);
  const int n = e.num_legs();
  std::vector<Box> boxes(num_steps);
  // The box of step j's foot: a point for the start stance and the history before it.
  auto foot_box = [&](int j) {
    if (j >= n) return boxes[j];
    const Eigen::Vector2d f(ConstantOf(e.Position(j, 0)), ConstantOf(e.Position(j, 1)));
    return Box(f, f);
  };
  for (int i = n; i < num_steps; ++i) {
    const int j = i - n;  // the leg's previous step: its nominal foot is the reach rows' centre
    const int cfg = j / n;
    const LegModel& leg = robot.legs[e.LegOfStep(i)];
    Box nominal;  // r_nom,j
    double yaw_lo = 0.0, yaw_hi = 0.0;
    if (j < n) {
      const Eigen::Vector2d r(ConstantOf(e.NominalFoot(j, 0)), ConstantOf(e.NominalFoot(j, 1)));
      nominal = Box(r, r);
      yaw_lo = yaw_hi = e.StartStepYaw(j);
    } else {
      Box centre(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());  // p_j, the mean of steps j - n + 1 .. j
      for (int k = j - n + 1; k <= j; ++k) centre = Sum(centre, foot_box(k));
      centre = Box(centre.min() / n, centre.max() / n);
      const int s = VariableOf(e.Sin(cfg)), c = VariableOf(e.Cos(cfg)), yaw = VariableOf(e.Yaw(cfg));
      nominal = Sum(centre, RotatedOffsetBox(leg.nominal_offset_body_m, b.lower(s), b.upper(s), b.lower(c), b.upper(c)));
      yaw_lo = b.lower(yaw);
      yaw_hi = b.upper(yaw);
    }
    const std::vector<Eigen::Vector2d> corners = ReachFaceCorners(leg.footprint_faces);
    boxes[i] = Sum(nominal, PolygonBox(corners, yaw_lo).intersection(PolygonBox(corners, yaw_hi)));
  }
  return boxes;
}

}  // namespace mfp
