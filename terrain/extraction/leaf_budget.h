#pragma once
// The work budget of cutting an occupancy map into per-column runs (surface_layers.h):
// every leaf n voxels wide becomes n^2 runs, one per x-y column it covers, so a handful
// of huge leaves costs more than millions of small ones. Checked before anything is
// expanded or allocated.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "base/round.h"
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

// The column cells LeafColumnCells counts for one free leaf: the part of its n^2 inside the
// occupied extent [x0, x1) x [y0, y1) (in voxels); 0 for a leaf it skips. Inline so that a
// pass computing the leaf's footprint as well shares the arithmetic.
inline double FreeLeafColumnCells(const OccupiedLeaf& leaf, double res, double x0, double y0, double x1, double y1) {
  const double n = leaf.size_m / res;
  if (!leaf.center_world_m.allFinite() || !std::isfinite(n) || n < 0.5) return 0.0;
  const double lx = RoundToDouble((leaf.center_world_m.x() - 0.5 * leaf.size_m) / res);
  const double ly = RoundToDouble((leaf.center_world_m.y() - 0.5 * leaf.size_m) / res);
  const double w = RoundToDouble(n);
  const double dx = std::min(lx + w, x1) - std::max(lx, x0), dy = std::min(ly + w, y1) - std::max(ly, y0);
  return dx > 0 && dy > 0 ? dx * dy : 0.0;
}

// LeafColumnCells' saturating conversion of an exact double sum of column cells.
inline uint64_t ColumnCellsFromSum(double total) {
  return total < 1.8e19 ? static_cast<uint64_t>(total) : UINT64_MAX;
}

// Throws InputError when LeafColumnCells(map) > max_leaf_columns, naming the count, the
// limit (SurfaceLayerOptions::max_leaf_columns) and what to do.
void CheckLeafColumnBudget(const OccupancyMap& map, uint64_t max_leaf_columns, int threads = 1);

}  // namespace mfp
