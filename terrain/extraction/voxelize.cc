#include "terrain/extraction/voxelize.h"

#include <cmath>
#include <sstream>

#include "base/check.h"

namespace mfp {

double OctreeHalfExtentM(double resolution_m) { return resolution_m * 32768.0; }

namespace {

std::string BoxName(const TerrainBox& box, size_t i) {
  return "terrain box " + std::to_string(i) + (box.name.empty() ? "" : " ('" + box.name + "')");
}

}  // namespace

OccupancyMap VoxelizeTerrain(const TerrainDescription& terrain, size_t max_voxel_tests) {
  const double res = terrain.resolution_m;
  if (!std::isfinite(res) || res < 0.001 || res > 1.0) {
    std::ostringstream msg;
    msg << "terrain resolution " << res << " m is outside the allowed range [0.001, 1] m";
    throw InputError(msg.str());
  }
  const double limit_m = OctreeHalfExtentM(res) - res;
  struct Range {
    Eigen::Vector3i lo, hi;
  };
  std::vector<Range> ranges;
  double total = 0.0;
  for (size_t i = 0; i < terrain.boxes.size(); ++i) {
    const TerrainBox& box = terrain.boxes[i];
    if (!box.center_world_m.allFinite() || !box.size_m.allFinite() || !box.rpy_rad.allFinite()) {
      throw InputError(BoxName(box, i) + ": centre, size and rpy must be finite numbers");
    }
    if ((box.size_m.array() <= 0.0).any()) {
      throw InputError(BoxName(box, i) + ": every size must be > 0 m");
    }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
    Eigen::Vector3d hi = -lo;
    for (const Eigen::Vector3d& c : BoxCorners(box)) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    if (lo.minCoeff() < -limit_m || hi.maxCoeff() > limit_m) {
      std::ostringstream msg;
      msg << BoxName(box, i) << ": reaches beyond +-" << limit_m
          << " m, the range an octree addresses at resolution " << res << " m";
      throw InputError(msg.str());
    }
    Range r;
    for (int a = 0; a < 3; ++a) {
      r.lo(a) = static_cast<int>(std::floor(lo(a) / res));
      r.hi(a) = static_cast<int>(std::ceil(hi(a) / res));
    }
    total += static_cast<double>((r.hi - r.lo).cast<double>().prod());
    if (total > static_cast<double>(max_voxel_tests)) {
      std::ostringstream msg;
      msg << BoxName(box, i) << ": the boxes' bounding volumes hold more than "
          << max_voxel_tests << " voxels at resolution " << res << " m";
      throw InputError(msg.str());
    }
    ranges.push_back(r);
  }

  OccupancyMap map;
  map.resolution_m = res;
  for (size_t i = 0; i < terrain.boxes.size(); ++i) {
    const TerrainBox& box = terrain.boxes[i];
    const Eigen::Matrix3d R_box_world = BoxRotation(box).transpose();
    // A tiny slack so faces lying exactly on voxel centres count as inside.
    const Eigen::Vector3d half = 0.5 * box.size_m + Eigen::Vector3d::Constant(1e-9);
    const Range& r = ranges[i];
    for (int kx = r.lo.x(); kx < r.hi.x(); ++kx) {
      for (int ky = r.lo.y(); ky < r.hi.y(); ++ky) {
        for (int kz = r.lo.z(); kz < r.hi.z(); ++kz) {
          const Eigen::Vector3d c((kx + 0.5) * res, (ky + 0.5) * res, (kz + 0.5) * res);
          const Eigen::Vector3d local = R_box_world * (c - box.center_world_m);
          if ((local.cwiseAbs().array() <= half.array()).all()) {
            map.leaves.push_back({c, res});
          }
        }
      }
    }
  }
  return map;
}

}  // namespace mfp
