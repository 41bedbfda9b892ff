#include "io/body_obstacles.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/convex_hull_2d.h"

namespace mfp {

std::vector<BodyObstacle> BoxBodyObstacles(const std::vector<TerrainBox>& boxes) {
  std::vector<BodyObstacle> obstacles;
  for (const TerrainBox& box : boxes) {
    // A box tilted about x or y is a ramp the feet stand on: its highest corner says
    // nothing about the surface under the body, so it is not an obstacle here (a body
    // check on ramps needs the surface height under the footprint: left for later).
    if (std::abs(box.rpy_rad.x()) > 1e-9 || std::abs(box.rpy_rad.y()) > 1e-9) continue;
    const Eigen::Matrix3d r = BoxRotation(box);
    BodyObstacle o;
    o.bottom_z_m = std::numeric_limits<double>::infinity();
    o.top_z_m = -o.bottom_z_m;
    std::vector<Eigen::Vector2d> corners;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d local(((c & 1) ? 0.5 : -0.5) * box.size_m.x(), ((c & 2) ? 0.5 : -0.5) * box.size_m.y(),
                                  ((c & 4) ? 0.5 : -0.5) * box.size_m.z());
      const Eigen::Vector3d p = box.center_world_m + r * local;
      corners.push_back(p.head<2>());
      o.bottom_z_m = std::min(o.bottom_z_m, p.z());
      o.top_z_m = std::max(o.top_z_m, p.z());
    }
    o.polygon_world_m = ConvexHull2d(corners);
    if (o.polygon_world_m.size() >= 3) obstacles.push_back(std::move(o));
  }
  return obstacles;
}

}  // namespace mfp
