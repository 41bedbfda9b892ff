#include "terrain/extraction/leaf_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "base/check.h"
#include "base/round.h"
#include "terrain/extraction/internal/parallel_work.h"

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

uint64_t LeafColumnCells(const OccupancyMap& map, int threads) {
  const double res = map.resolution_m;
  if (!std::isfinite(res) || res <= 0.0) return 0;
  // Summed in double: every term and every partial sum is a whole number, exact below
  // 2^53 in any order, and the total only compared. The leaves in `parts` ranges at once.
  const int parts = std::max(1, threads);
  auto range = [parts](size_t n, int p) {
    return std::make_pair(n * static_cast<size_t>(p) / static_cast<size_t>(parts),
                          n * static_cast<size_t>(p + 1) / static_cast<size_t>(parts));
  };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> occupied(static_cast<size_t>(parts), 0.0), free(static_cast<size_t>(parts), 0.0);
  std::vector<CellBox> extents(static_cast<size_t>(parts), CellBox{inf, inf, -inf, -inf});
  ParallelFor(parts, threads, [&](int p) {
    CellBox& extent = extents[static_cast<size_t>(p)];
    const auto [begin, end] = range(map.leaves.size(), p);
    for (size_t i = begin; i < end; ++i) {
      CellBox b;
      if (!BoxOf(map.leaves[i], res, &b)) continue;
      occupied[static_cast<size_t>(p)] += (b.x1 - b.x0) * (b.y1 - b.y0);
      extent = {std::min(extent.x0, b.x0), std::min(extent.y0, b.y0), std::max(extent.x1, b.x1),
                std::max(extent.y1, b.y1)};
    }
  });
  CellBox extent = extents.front();
  for (const CellBox& e : extents) {
    extent = {std::min(extent.x0, e.x0), std::min(extent.y0, e.y0), std::max(extent.x1, e.x1), std::max(extent.y1, e.y1)};
  }
  ParallelFor(parts, threads, [&](int p) {
    const auto [begin, end] = range(map.free_leaves.size(), p);
    for (size_t i = begin; i < end; ++i) {
      free[static_cast<size_t>(p)] += FreeLeafColumnCells(map.free_leaves[i], res, extent.x0, extent.y0, extent.x1, extent.y1);
    }
  });
  double total = 0.0;
  for (int p = 0; p < parts; ++p) total += occupied[static_cast<size_t>(p)] + free[static_cast<size_t>(p)];
  return ColumnCellsFromSum(total);
}

void CheckLeafColumnBudget(const OccupancyMap& map, uint64_t max_leaf_columns, int threads) {
  const uint64_t cells = LeafColumnCells(map, threads);
  if (cells <= max_leaf_columns) return;
  std::ostringstream msg;
  msg << "occupancy map: its leaves cover " << cells << " x-y column cells (a leaf n voxels "
      << "wide counts n^2), more than the extraction's limit of " << max_leaf_columns
      << " (SurfaceLayerOptions::max_leaf_columns, about 32 bytes a cell): give a map of the "
      << "terrain near the robot, or raise that limit where the regions are extracted";
  throw InputError(msg.str());
}

}  // namespace mfp
