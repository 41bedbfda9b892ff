#include "planner/robot/reach_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/check.h"
#include "geometry/convex_hull_2d.h"

namespace mfp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double Support(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& u) {
  double h = -kInf;
  for (const Eigen::Vector2d& p : poly) h = std::max(h, u.dot(p));
  return h;
}

// Outward-or-inward edge normals (both signs are tried by the caller).
void AddEdgeNormals(const std::vector<Eigen::Vector2d>& poly, std::vector<Eigen::Vector2d>* axes) {
  for (size_t k = 0; k < poly.size(); ++k) {
    const Eigen::Vector2d edge = poly[(k + 1) % poly.size()] - poly[k];
    const double length = edge.norm();
    if (length > 1e-12) axes->emplace_back(-edge.y() / length, edge.x() / length);
  }
}

}  // namespace

std::vector<Eigen::Vector2d> ReachPolygon(ReachShape shape, double half_width_m) {
  const double a = half_width_m;
  if (shape == ReachShape::kBox) return {{a, -a}, {a, a}, {-a, a}, {-a, -a}};
  // The regular polygon of apothem a, its edges' normals at multiples of 2 pi / sides from x
  // (sides a multiple of 8): its corners at angles (2j + 1) pi / sides, a / cos(pi / sides)
  // from the centre. Those below the diagonal are computed, the rest mirrored from them, so
  // that corners on one edge line share its coordinate exactly (the step polygon's hull
  // then drops no corner and keeps no near-collinear one).
  const int sides = ReachShapeSides(shape);
  const double radius = a / std::cos(M_PI / sides);
  std::vector<Eigen::Vector2d> octant = {{a, a * std::tan(M_PI / sides)}};
  for (int j = 1; 4 * (2 * j + 1) < sides; ++j) {
    const double angle = (2 * j + 1) * M_PI / sides;
    octant.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  std::vector<Eigen::Vector2d> quadrant = octant;
  for (auto it = octant.rbegin(); it != octant.rend(); ++it) quadrant.emplace_back(it->y(), it->x());
  // Counter-clockwise from the corner just below the x axis: the quadrants turned by pi/2.
  std::vector<Eigen::Vector2d> corners = {{a, -octant.front().y()}};
  for (int turn = 0; turn < 4; ++turn) {
    for (size_t k = 0; k < quadrant.size(); ++k) {
      if (turn == 3 && k + 1 == quadrant.size()) break;  // the first corner, already placed
      const Eigen::Vector2d& q = quadrant[k];
      corners.push_back(turn == 0 ? q : turn == 1 ? Eigen::Vector2d(-q.y(), q.x())
                                        : turn == 2 ? Eigen::Vector2d(-q.x(), -q.y()) : Eigen::Vector2d(q.y(), -q.x()));
    }
  }
  return corners;
}

double FootprintInscribedReach(const RobotModel& robot) {
  double reach = kInf;
  for (const LegModel& leg : robot.legs) {
    for (const ReachFace& f : leg.footprint_faces) reach = std::min(reach, f.offset_m);
  }
  return reach;
}

double FootprintFarthestCorner(const LegModel& leg) {
  double far = 0.0;
  for (const Eigen::Vector2d& c : ReachFaceCorners(leg.footprint_faces)) far = std::max(far, c.norm());
  return far;
}

double FootprintDiameter(const LegModel& leg) {
  // A polygon's widest width over every direction is its diameter, the largest distance
  // between two of its corners.
  const std::vector<Eigen::Vector2d> corners = ReachFaceCorners(leg.footprint_faces);
  double widest = 0.0;
  for (const Eigen::Vector2d& a : corners) {
    for (const Eigen::Vector2d& b : corners) widest = std::max(widest, (a - b).norm());
  }
  return widest;
}

double FootprintStepWidth(const RobotModel& robot) {
  double narrowest = kInf;
  for (const LegModel& leg : robot.legs) narrowest = std::min(narrowest, FootprintDiameter(leg));
  return narrowest;
}

double AxisStepSpan(const RobotModel& robot) {
  return robot.reach_shape == ReachShape::kFootprint ? FootprintStepWidth(robot) : robot.d_lim_m + robot.l_bnd_m;
}

const char* AxisStepSpanName(const RobotModel& robot) {
  return robot.reach_shape == ReachShape::kFootprint ? "the footprint polygon's width" : "d_lim + l_bnd";
}

std::vector<Eigen::Vector2d> StepPolygon(const RobotModel& robot) {
  if (robot.reach_shape == ReachShape::kFootprint) {
    // The old foot anywhere in the polygon about r_nom,i-n, the new one too, at a yaw the
    // windows choose: the regular 16-gon whose apothem is the polygon's widest width (an
    // over-approximation: the route graph may join what a window's yaw range cannot cross).
    return ReachPolygon(ReachShape::kHexadecagon, FootprintStepWidth(robot));
  }
  const std::vector<Eigen::Vector2d> reach = ReachPolygon(robot.reach_shape, robot.d_lim_m);
  const std::vector<Eigen::Vector2d> box = ReachPolygon(ReachShape::kBox, robot.l_bnd_m);
  std::vector<Eigen::Vector2d> sums;
  for (const Eigen::Vector2d& r : reach) {
    for (const Eigen::Vector2d& q : box) sums.push_back(r + q);
  }
  return ConvexHull2d(sums);
}

double StepsToBridge(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                     const std::vector<Eigen::Vector2d>& step) {
  MFP_CHECK(!a.empty() && !b.empty() && step.size() >= 3);
  std::vector<Eigen::Vector2d> axes;
  AddEdgeNormals(a, &axes);
  AddEdgeNormals(b, &axes);
  AddEdgeNormals(step, &axes);
  if (a.size() == 1 && b.size() == 1 && (b[0] - a[0]).norm() > 0) axes.push_back((b[0] - a[0]).normalized());
  // a + t step misses b exactly when an edge normal u of the three separates them:
  // max_a u.p + t h_step(u) < min_b u.q; the smallest t that meets b is the largest
  // such bound over the normals, both signs.
  double t = 0.0;
  for (const Eigen::Vector2d& axis : axes) {
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector2d u = sign * axis;
      const double gap = -Support(b, -u) - Support(a, u);
      const double reach = Support(step, u);
      MFP_CHECK(reach > 0.0);
      t = std::max(t, gap / reach);
    }
  }
  return t;
}

double StepReachAlong(const std::vector<Eigen::Vector2d>& step, const Eigen::Vector2d& d) {
  MFP_CHECK(d.norm() > 0.0 && step.size() >= 3);
  const Eigen::Vector2d u = d.normalized();
  // The ray from the origin leaves the convex polygon through the edge whose line it
  // meets first: the smallest positive distance to an edge line along u.
  double reach = kInf;
  for (size_t k = 0; k < step.size(); ++k) {
    const Eigen::Vector2d p = step[k], q = step[(k + 1) % step.size()];
    const Eigen::Vector2d edge = q - p;
    const Eigen::Vector2d normal(edge.y(), -edge.x());  // outward for a counter-clockwise polygon
    const double along = normal.dot(u);
    if (along > 1e-15) reach = std::min(reach, normal.dot(p) / along);
  }
  return reach;
}

}  // namespace mfp
