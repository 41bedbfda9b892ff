#include "geometry/plan_bounds.h"

namespace mfp {

Eigen::AlignedBox2d PlanBounds(const ConvexRegion& region) {
  Eigen::AlignedBox2d box;  // empty
  for (const Eigen::Vector3d& v : region.vertices_world_m) box.extend(v.head<2>());
  return box;
}

}  // namespace mfp
