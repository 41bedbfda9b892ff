#include "planner/formulation/internal/region_union_hull.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/check.h"
#include "geometry/convex_hull_2d.h"

namespace mfp {

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
  const std::vector<Eigen::Vector2d> hull = ConvexHull2d(points);
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
