#include "planner/planning/stance_snap.h"

#include <algorithm>
#include <cmath>

namespace mfp {

Eigen::Vector3d SnapIntoRegion(const ConvexRegion& region, const Eigen::Vector3d& p, double inside_m) {
  if (region.vertices_world_m.empty() || region.A.rows() == 0) return p;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : region.vertices_world_m) centre += v;
  centre /= static_cast<double>(region.vertices_world_m.size());
  // The polygon's edges are vertical rows; along the segment p + t (centre - p) each is
  // linear in t: g_j(t) = (1-t) g_j(0) + t g_j(1). The plane's two rows (a slab of
  // 2 plane_tolerance, possibly 0) are met by putting the foot on the plane afterwards.
  double t = 0.0;
  for (int j = 0; j < region.A.rows(); ++j) {
    const Eigen::Vector3d a = region.A.row(j).transpose();
    if (std::abs(a.z()) > 1e-9 * a.norm()) continue;
    const double spare = inside_m * a.norm();
    const double at_p = a.dot(p) - region.b(j) + spare;
    if (at_p <= 0.0) continue;
    const double at_centre = a.dot(centre) - region.b(j) + spare;
    // A region narrower than the spare: go as far as the centre (the best the segment has).
    t = at_centre >= 0.0 ? 1.0 : std::max(t, at_p / (at_p - at_centre));
  }
  Eigen::Vector3d q = p + std::min(1.0, t) * (centre - p);
  q.z() = region.HeightAt(q.x(), q.y());
  return q;
}

const ConvexRegion* RegionWithId(const std::vector<ConvexRegion>& regions, int region_id) {
  for (const ConvexRegion& r : regions) {
    if (r.id == region_id) return &r;
  }
  return nullptr;
}

}  // namespace mfp
