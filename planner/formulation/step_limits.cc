#include "planner/formulation/step_limits.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "base/check.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {

namespace {

// How far the shared offsets' bounds lie beyond the footprint rows' bounding box [m]: the
// bounds are implied by the rows, and kept off the polygon's corners so that they are never
// active at an optimum (a bound active with two face rows at one corner is degenerate).
constexpr double kSharedOffsetMargin = 0.01;

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

// The footprint polygon of step i's leg about the nominal foot of step j (j = i: the
// reference rows, j = i - n: the reachability rows), at every yaw configuration b(j) may
// take: for yaws psi spaced at most kFootprintYawSpacing apart over its range [lo, hi],
// (R(psi) u_k) . (f_i - r_nom,j) <= h_k - |w|max (1 - cos(spacing / 2)) for each face
// (u_k, h_k). Between two neighbouring psi the turned normal lies within 1 - cos(spacing /
// 2) of their chord, so the rows at the two ends, shrunk by that sagitta times the farthest
// corner |w|max, imply the face at every yaw between them. One yaw (the validator's, the
// start's): the faces themselves, unshrunk.
void AddFootprintFaces(StepEncoder& e, const RobotModel& robot, int i, int j, RowKind kind, const char* what) {
  const LegModel& leg = robot.legs[e.LegOfStep(i)];
  const auto [lo, hi] = e.YawBounds(j);
  MFP_CHECK(std::isfinite(lo) && std::isfinite(hi));
  const int pieces = hi > lo ? static_cast<int>(std::ceil((hi - lo) / kFootprintYawSpacing - 1e-9)) : 0;
  const double spacing = pieces > 0 ? (hi - lo) / pieces : 0.0;
  const double sagitta = FootprintFarthestCorner(leg) * (1.0 - std::cos(0.5 * spacing));
  std::vector<ReachFace> rows;
  for (int p = 0; p <= pieces; ++p) {
    const double psi = pieces > 0 ? lo + spacing * p : lo;
    for (const ReachFace& face : leg.footprint_faces) {
      rows.push_back({Eigen::Rotation2Dd(psi) * face.normal, face.offset_m - sagitta});
    }
  }
  // Only the rows whose line touches the rows' intersection: the others are implied by them
  // (the intersection is the same polygon, with fewer rows for the solver).
  const std::vector<Eigen::Vector2d> corners = ReachFaceCorners(rows);
  StepExpr dx = e.Position(i, 0) - e.NominalFoot(j, 0);
  StepExpr dy = e.Position(i, 1) - e.NominalFoot(j, 1);
  // The offset f_i - r_nom,j as two quantities of its own (StepEncoder::Shared) when it is
  // more than the foot's position: each face row then touches two variables, not the
  // centre of contacts' and the yaw's too. Their bounds are the polygon's bounding box
  // widened by kSharedOffsetMargin, which the rows imply.
  if (dx.lin.terms.size() > 1 && !corners.empty()) {
    Eigen::Vector2d lo = corners.front(), hi = corners.front();
    for (const Eigen::Vector2d& c : corners) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    const double m = kSharedOffsetMargin;
    dx = e.Shared(StepName((std::string(what) + "_wx").c_str(), i), dx, lo.x() - m, hi.x() + m);
    dy = e.Shared(StepName((std::string(what) + "_wy").c_str(), i), dy, lo.y() - m, hi.y() + m);
  }
  for (size_t k = 0; k < rows.size(); ++k) {
    double touch = -kInfinity;
    for (const Eigen::Vector2d& c : corners) touch = std::max(touch, rows[k].normal.dot(c));
    if (!corners.empty() && touch < rows[k].offset_m - 1e-9) continue;
    const Eigen::Vector2d& u = rows[k].normal;
    e.AddRow(kind, StepName((std::string(what) + "_" + std::to_string(k)).c_str(), i),
             FoldRotations(u.x() * dx + u.y() * dy), -kInfinity, rows[k].offset_m);
  }
}

}  // namespace

void AddStepLimits(StepEncoder& e, const RobotModel& robot, int i) {
  const int n = e.num_legs();
  if (robot.reach_shape == ReachShape::kFootprint) {
    AddFootprintFaces(e, robot, i, i, RowKind::kReferenceBox, "ref_fp");
    AddFootprintFaces(e, robot, i, i - n, RowKind::kReachability, "reach_fp");
    e.AddRow(RowKind::kHeightChange, StepName("dz", i), e.Position(i, 2) - e.Position(i - n, 2), -robot.dz_max_m,
             robot.dz_max_m);
    return;
  }
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
  if (robot.reach_shape == ReachShape::kFootprint) {
    // A leg's first move: its polygon, turned to any yaw, lies within its farthest corner of
    // the nominal foot. A later move f_i - f_i-n: both feet lie in the leg's polygon about
    // r_nom,i-n (the reach rows of step i, the reference rows of step i - n) turned by the
    // same yaw, that of configuration b(i - n), so the move is at most the polygon's diameter.
    for (int i = n; i < num_steps; ++i) {
      const LegModel& leg = robot.legs[e.LegOfStep(i)];
      moves[i] = i - n < n ? FootprintFarthestCorner(leg) + start_offset[i - n] : FootprintDiameter(leg);
    }
    return moves;
  }
  for (int i = n; i < num_steps; ++i) moves[i] = robot.d_lim_m + (i - n < n ? start_offset[i - n] : robot.l_bnd_m);
  return moves;
}

}  // namespace mfp
