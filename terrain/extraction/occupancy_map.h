#pragma once
// Occupied (and known free) space of a terrain map as plain Eigen data: the leaves of an
// octree.
// Pruned leaves are cubes larger than the resolution (resolution * 2^k). Filled by the
// OctoMap adapter (octomap_io.h) or by voxelising a terrain description (voxelize.h);
// read by the height map (height_map.h). No OctoMap types cross this boundary.
#include <Eigen/Core>
#include <vector>

namespace mfp {

struct OccupiedLeaf {
  Eigen::Vector3d center_world_m = Eigen::Vector3d::Zero();  // cube centre [m, world]
  double size_m = 0.0;                                      // cube edge length [m]
};

struct OccupancyMap {
  double resolution_m = 0.0;  // smallest voxel edge [m]
  std::vector<OccupiedLeaf> leaves;
  // Leaves known to be free (space a sensor's rays passed through). Empty when the map
  // stores no free space (mfp-terrain's box maps): then nothing is known about free space.
  std::vector<OccupiedLeaf> free_leaves;
};

}  // namespace mfp
