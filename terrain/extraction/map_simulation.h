#pragma once
// Maps made from a box description the way a robot's sensor makes them: rays cast from
// sensor positions (occupied where they hit, free where they pass), and scan noise
// (floors off by a voxel, holes, isolated outlier voxels). Plain Eigen, seeded and
// repeatable; mfp-terrain writes the result as an OctoMap file and the tests extract
// regions from it.
#include <cstddef>

#include "geometry/terrain_description.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

// Largest number of voxels in the grid a scan is cast into.
constexpr size_t kDefaultMaxScanVoxels = 60'000'000;

// Casts rays from each sensor over the whole sphere, at an angular step that puts
// neighbouring rays half a voxel apart at max_range. Every voxel a ray first hits is
// occupied; the voxels it passes through before are free unless some ray hit them.
// Leaves are single voxels. Throws InputError on a bad description (as VoxelizeTerrain),
// no sensors, a sensor inside a box, max_range not in (0, 100] m, or a grid larger than
// max_voxels.
OccupancyMap ScanTerrain(const TerrainDescription& terrain,
                         size_t max_voxels = kDefaultMaxScanVoxels);

// Applies the noise to a map of single-voxel leaves (ScanTerrain's or VoxelizeTerrain's).
void AddMapNoise(const MapNoise& noise, OccupancyMap* map);

// The map a description stands for: ScanTerrain when it has sensors, else
// VoxelizeTerrain; then its noise.
OccupancyMap MakeTerrainMap(const TerrainDescription& terrain);

}  // namespace mfp
