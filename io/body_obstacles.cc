#include "io/body_obstacles.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mfp {

std::vector<Eigen::Vector2d> ConvexHull2D(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

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
    o.polygon_world_m = ConvexHull2D(corners);
    if (o.polygon_world_m.size() >= 3) obstacles.push_back(std::move(o));
  }
  return obstacles;
}

}  // namespace mfp
