#pragma once
// Turns a box terrain description into occupied voxels on the octree grid (voxel centres
// at (k + 1/2) * resolution, as OctoMap keys them). A voxel is occupied when its centre
// lies inside a box. Plain Eigen, no OctoMap: the extractor's tests and the benchmark
// use it directly, and WriteTerrainMap (octomap_io.h) stores the result as a file.
#include <cstddef>

#include "geometry/terrain_description.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

// Largest number of voxel centres tested for one description (bounds time and memory).
constexpr size_t kDefaultMaxVoxelTests = 50'000'000;

// Throws InputError when the resolution is outside [0.001, 1] m, a box is not finite or
// has a size <= 0, a box reaches beyond the octree's addressable range, or the boxes'
// bounding volumes hold more than max_voxel_tests voxels.
OccupancyMap VoxelizeTerrain(const TerrainDescription& terrain,
                             size_t max_voxel_tests = kDefaultMaxVoxelTests);

// Half-width of the cube an OctoMap tree of 16 levels addresses at this resolution [m].
double OctreeHalfExtentM(double resolution_m);

}  // namespace mfp
