#include "planner/region_union_hull.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planner/check.h"

namespace mfp {
namespace {

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Andrew's monotone chain: the hull's vertices counter-clockwise, without collinear ones.
std::vector<Eigen::Vector2d> HullCounterClockwise(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower_size = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower_size && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

}  // namespace

RegionUnionHull HullOfRegions(const std::vector<const ConvexRegion*>& regions) {
  MFP_CHECK(!regions.empty());
  RegionUnionHull h;
  std::vector<Eigen::Vector2d> points;
  h.z_lower_m = std::numeric_limits<double>::infinity();
  h.z_upper_m = -std::numeric_limits<double>::infinity();
  for (const ConvexRegion* r : regions) {
    for (const Eigen::Vector3d& v : r->vertices_world_m) {
      points.push_back(v.head<2>());
      h.z_lower_m = std::min(h.z_lower_m, v.z() - r->plane_tolerance_m);
      h.z_upper_m = std::max(h.z_upper_m, v.z() + r->plane_tolerance_m);
    }
  }
  const std::vector<Eigen::Vector2d> hull = HullCounterClockwise(points);
  std::vector<std::pair<Eigen::Vector2d, double>> rows;
  if (hull.size() >= 3) {
    for (size_t k = 0; k < hull.size(); ++k) {
      const Eigen::Vector2d edge = hull[(k + 1) % hull.size()] - hull[k];
      Eigen::Vector2d normal = Eigen::Vector2d(edge.y(), -edge.x()).normalized();  // outward for CCW
      // An axis-aligned edge gets an exact axis normal (no 1e-17 component).
      for (int axis = 0; axis < 2; ++axis) {
        if (std::abs(normal(axis)) < 1e-12) normal(axis) = 0.0;
      }
      normal.normalize();
      rows.emplace_back(normal, normal.dot(hull[k]));
    }
  } else {
    // A segment or a point: bound it along its direction and across it.
    const Eigen::Vector2d a = hull.front(), b = hull.back();
    const Eigen::Vector2d along = (b - a).norm() > 0.0 ? Eigen::Vector2d((b - a).normalized()) : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d across(-along.y(), along.x());
    rows.emplace_back(along, along.dot(b));
    rows.emplace_back(-along, -along.dot(a));
    rows.emplace_back(across, across.dot(a));
    rows.emplace_back(-across, -across.dot(a));
  }
  h.A.resize(static_cast<Eigen::Index>(rows.size()), 2);
  h.b.resize(static_cast<Eigen::Index>(rows.size()));
  for (size_t k = 0; k < rows.size(); ++k) {
    h.A.row(static_cast<Eigen::Index>(k)) = rows[k].first.transpose();
    h.b(static_cast<Eigen::Index>(k)) = rows[k].second;
  }
  return h;
}

}  // namespace mfp
