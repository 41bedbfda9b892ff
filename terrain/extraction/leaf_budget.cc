#include "terrain/extraction/leaf_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "base/check.h"
#include "base/round.h"

namespace mfp {
namespace {

// A leaf's x-y cell range [x0, x1) x [y0, y1) on the map's grid, in voxels.
struct CellBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

bool BoxOf(const OccupiedLeaf& leaf, double res, CellBox* box) {
  const double n = leaf.size_m / res;
  if (!leaf.center_world_m.allFinite() || !std::isfinite(n) || n < 0.5) return false;
  const double x0 = RoundToDouble((leaf.center_world_m.x() - 0.5 * leaf.size_m) / res);
  const double y0 = RoundToDouble((leaf.center_world_m.y() - 0.5 * leaf.size_m) / res);
  const double w = RoundToDouble(n);
  *box = {x0, y0, x0 + w, y0 + w};
  return true;
}

}  // namespace

uint64_t LeafColumnCells(const OccupancyMap& map) {
  const double res = map.resolution_m;
  if (!std::isfinite(res) || res <= 0.0) return 0;
  // Summed in double: every term is exact below 2^53 and the total only compared.
  double occupied = 0.0;
  CellBox extent{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                 -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const OccupiedLeaf& leaf : map.leaves) {
    CellBox b;
    if (!BoxOf(leaf, res, &b)) continue;
    occupied += (b.x1 - b.x0) * (b.y1 - b.y0);
    extent = {std::min(extent.x0, b.x0), std::min(extent.y0, b.y0), std::max(extent.x1, b.x1),
              std::max(extent.y1, b.y1)};
  }
  double free = 0.0;
  for (const OccupiedLeaf& leaf : map.free_leaves) {
    CellBox b;
    if (!BoxOf(leaf, res, &b)) continue;
    const double w = std::min(b.x1, extent.x1) - std::max(b.x0, extent.x0);
    const double h = std::min(b.y1, extent.y1) - std::max(b.y0, extent.y0);
    if (w > 0 && h > 0) free += w * h;
  }
  const double total = occupied + free;
  if (!(total < 1.8e19)) return std::numeric_limits<uint64_t>::max();
  return static_cast<uint64_t>(total);
}

void CheckLeafColumnBudget(const OccupancyMap& map, uint64_t max_leaf_columns) {
  const uint64_t cells = LeafColumnCells(map);
  if (cells <= max_leaf_columns) return;
  std::ostringstream msg;
  msg << "occupancy map: its leaves cover " << cells << " x-y column cells (a leaf n voxels "
      << "wide counts n^2), more than the extraction's limit of " << max_leaf_columns
      << " (SurfaceLayerOptions::max_leaf_columns, about 32 bytes a cell): give a map of the "
      << "terrain near the robot, or raise that limit where the regions are extracted";
  throw InputError(msg.str());
}

}  // namespace mfp
