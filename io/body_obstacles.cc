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

std::vector<BodyObstacle> PrismBodyObstacles(const std::vector<MapPrism>& prisms) {
  std::vector<BodyObstacle> obstacles;
  obstacles.reserve(prisms.size());
  for (const MapPrism& p : prisms) {
    BodyObstacle o;
    o.polygon_world_m = {p.min_world_m, Eigen::Vector2d(p.max_world_m.x(), p.min_world_m.y()), p.max_world_m,
                         Eigen::Vector2d(p.min_world_m.x(), p.max_world_m.y())};
    o.bottom_z_m = p.bottom_z_m;
    o.top_z_m = p.top_z_m;
    obstacles.push_back(std::move(o));
  }
  return obstacles;
}

std::optional<MapObstacleOptions> BodyMapObstacleOptions(const std::vector<const RobotModel*>& robots) {
  std::optional<MapObstacleOptions> options;
  for (const RobotModel* robot : robots) {
    const BodyExtent& body = robot->body;
    if (!body.known()) continue;
    const double box_radius = body.min_m.cwiseAbs().cwiseMax(body.max_m.cwiseAbs()).norm();
    const double radius = box_radius + LegReach(*robot) + std::sqrt(2.0) * (robot->l_bnd_m + robot->d_lim_m);
    if (!options) {
      options = MapObstacleOptions();
      options->floor_band_m = std::max(0.0, body.bottom_m);
      options->ground_radius_m = radius;
    }
    options->floor_band_m = std::min(options->floor_band_m, std::max(0.0, body.bottom_m));
    options->ground_radius_m = std::max(options->ground_radius_m, radius);
  }
  return options;
}

}  // namespace mfp
