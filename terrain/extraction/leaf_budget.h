#pragma once
// The work budget of cutting an occupancy map into per-column runs (surface_layers.h):
// every leaf n voxels wide becomes n^2 runs, one per x-y column it covers, so a handful
// of huge leaves costs more than millions of small ones. Checked before anything is
// expanded or allocated.
#include <cstdint>

#include "terrain/extraction/occupancy_map.h"

namespace mfp {

// Default cap on the column cells a map's leaves cover: 2^25 runs, about 0.5 GB while
// the columns are built and sorted.
constexpr uint64_t kDefaultMaxLeafColumns = uint64_t{1} << 25;

// Column cells the leaves of `map` expand to: n^2 for every occupied leaf n voxels wide,
// and for every free leaf the part of its n^2 inside the occupied leaves' x-y extent (the
// only columns the extraction looks at). Leaves that are not finite cubes of at least one
// voxel are skipped (BuildHeightMap refuses them). Saturates at UINT64_MAX. The leaves
// are summed in `threads` parts at once (the count does not depend on it).
uint64_t LeafColumnCells(const OccupancyMap& map, int threads = 1);

// Throws InputError when LeafColumnCells(map) > max_leaf_columns, naming the count, the
// limit (SurfaceLayerOptions::max_leaf_columns) and what to do.
void CheckLeafColumnBudget(const OccupancyMap& map, uint64_t max_leaf_columns, int threads = 1);

}  // namespace mfp
