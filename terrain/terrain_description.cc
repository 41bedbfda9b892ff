#include "terrain/terrain_description.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "planner/base/check.h"

namespace mfp {

Eigen::Matrix3d BoxRotation(const TerrainBox& box) {
  return (Eigen::AngleAxisd(box.rpy_rad.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(box.rpy_rad.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(box.rpy_rad.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::vector<Eigen::Vector3d> BoxCorners(const TerrainBox& box) {
  const Eigen::Matrix3d R = BoxRotation(box);
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    corners.push_back(box.center_world_m + R * (0.5 * sign.cwiseProduct(box.size_m)));
  }
  return corners;
}

std::vector<ConvexRegion> TopFaceRegions(const TerrainDescription& terrain, double inset_m,
                                         double max_slope_rad) {
  std::vector<ConvexRegion> regions;
  for (size_t i = 0; i < terrain.boxes.size(); ++i) {
    const TerrainBox& box = terrain.boxes[i];
    const std::string name = "terrain box " + std::to_string(i) +
                             (box.name.empty() ? "" : " ('" + box.name + "')");
    if (!box.center_world_m.allFinite() || !box.size_m.allFinite() || !box.rpy_rad.allFinite()) {
      throw InputError(name + ": centre, size and rpy must be finite numbers");
    }
    if ((box.size_m.array() <= 0.0).any()) {
      throw InputError(name + ": every size must be > 0 m");
    }
    const Eigen::Matrix3d R = BoxRotation(box);
    // Pick the box axis (with sign) most aligned with world up.
    int axis = 0;
    double best = -2.0;
    double sign = 1.0;
    for (int a = 0; a < 3; ++a) {
      for (double s : {1.0, -1.0}) {
        const double up = s * R(2, a);
        if (up > best) {
          best = up;
          axis = a;
          sign = s;
        }
      }
    }
    const double slope = std::acos(std::min(1.0, best));
    if (slope > max_slope_rad) continue;
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    const double half_u = 0.5 * box.size_m(u) - inset_m;
    const double half_v = 0.5 * box.size_m(v) - inset_m;
    if (half_u <= 1e-6 || half_v <= 1e-6) continue;
    const Eigen::Vector3d face_center =
        box.center_world_m + R.col(axis) * (sign * 0.5 * box.size_m(axis));
    std::vector<Eigen::Vector3d> vertices;
    const std::array<std::array<double, 2>, 4> corners = {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
    for (const auto& c : corners) {
      vertices.push_back(face_center + R.col(u) * (c[0] * half_u) + R.col(v) * (c[1] * half_v));
    }
    regions.push_back(
        MakeRegionFromPolygon(static_cast<int>(regions.size()), vertices, 0.0));
  }
  return regions;
}

}  // namespace mfp
