#include "terrain/extraction/map_body_obstacles.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include "base/check.h"
#include "terrain/extraction/leaf_budget.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

// A column's run of occupied voxels kb..kt (inclusive) at plan cell (ix, iy), in voxels.
struct Run {
  int32_t ix = 0, iy = 0, kb = 0, kt = 0;
};

// Plan cells ix0..ix1 x iy0..iy1 (inclusive) over voxels kb..kt.
struct CellPrism {
  int32_t ix0 = 0, ix1 = 0, iy0 = 0, iy1 = 0, kb = 0, kt = 0;
};

constexpr double kMaxIndex = 1 << 30;  // voxel indices stay well inside int32

// The leaf's voxel range: its lowest corner and its width, in voxels; false when the leaf
// is not a finite cube of at least one voxel inside the index range.
bool VoxelRange(const OccupiedLeaf& leaf, double res, int32_t corner[3], int32_t* width) {
  const double n = std::round(leaf.size_m / res);
  if (!leaf.center_world_m.allFinite() || !std::isfinite(n) || n < 1.0) return false;
  for (int a = 0; a < 3; ++a) {
    const double c = std::round((leaf.center_world_m[a] - 0.5 * leaf.size_m) / res);
    if (std::abs(c) > kMaxIndex) return false;
    corner[a] = static_cast<int32_t>(c);
  }
  *width = static_cast<int32_t>(n);
  return true;
}

// Every column's runs, sorted by (iy, ix, kb), touching runs merged.
std::vector<Run> ColumnRuns(const OccupancyMap& map, uint64_t cells) {
  std::vector<Run> runs;
  runs.reserve(cells);
  for (const OccupiedLeaf& leaf : map.leaves) {
    int32_t c[3], n = 0;
    if (!VoxelRange(leaf, map.resolution_m, c, &n)) continue;
    for (int32_t dy = 0; dy < n; ++dy) {
      for (int32_t dx = 0; dx < n; ++dx) runs.push_back({c[0] + dx, c[1] + dy, c[2], c[2] + n - 1});
    }
  }
  std::sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) {
    return std::tie(a.iy, a.ix, a.kb) < std::tie(b.iy, b.ix, b.kb);
  });
  std::vector<Run> merged;
  for (const Run& r : runs) {
    if (!merged.empty() && merged.back().ix == r.ix && merged.back().iy == r.iy && r.kb <= merged.back().kt + 1) {
      merged.back().kt = std::max(merged.back().kt, r.kt);
    } else {
      merged.push_back(r);
    }
  }
  return merged;
}

// Plan grid of the runs' extent: per cell, the lowest run top (INT32_MAX: no run).
struct LowGrid {
  int32_t x0 = 0, y0 = 0, nx = 0, ny = 0;
  std::vector<int32_t> low;
  int32_t& at(int32_t ix, int32_t iy) { return low[static_cast<size_t>(iy - y0) * nx + (ix - x0)]; }
};

// One pass of a square minimum filter of half-width r along x (step 1) or y (step nx).
void MinPass(std::vector<int32_t>* values, int32_t lines, int32_t length, int32_t along, int32_t across,
             int32_t r) {
  std::vector<int32_t> line(length), out(length);
  for (int32_t l = 0; l < lines; ++l) {
    for (int32_t i = 0; i < length; ++i) line[i] = (*values)[static_cast<size_t>(l) * across + i * along];
    for (int32_t i = 0; i < length; ++i) {
      int32_t m = INT32_MAX;
      for (int32_t j = std::max(0, i - r); j <= std::min(length - 1, i + r); ++j) m = std::min(m, line[j]);
      out[i] = m;
    }
    for (int32_t i = 0; i < length; ++i) (*values)[static_cast<size_t>(l) * across + i * along] = out[i];
  }
}

// The lowest run top within r cells (a square, which holds the disk) of every cell.
void LowestAround(LowGrid* grid, int32_t r) {
  MinPass(&grid->low, grid->ny, grid->nx, 1, grid->nx, r);
  MinPass(&grid->low, grid->nx, grid->ny, grid->nx, 1, r);
}

// Row iy's kept runs as segments of consecutive cells with one (kb, kt), extending the
// prisms of row iy - 1 with the same span and band (`open`: span and band -> prism index).
using SpanKey = std::tuple<int32_t, int32_t, int32_t, int32_t>;  // ix0, ix1, kb, kt
void MergeRow(std::vector<Run> row, int32_t iy, std::map<SpanKey, size_t>* open, std::vector<CellPrism>* prisms) {
  std::sort(row.begin(), row.end(),
            [](const Run& a, const Run& b) { return std::tie(a.kb, a.kt, a.ix) < std::tie(b.kb, b.kt, b.ix); });
  std::map<SpanKey, size_t> next;
  for (size_t i = 0; i < row.size();) {
    size_t j = i + 1;
    while (j < row.size() && row[j].kb == row[i].kb && row[j].kt == row[i].kt && row[j].ix == row[j - 1].ix + 1) ++j;
    const SpanKey key{row[i].ix, row[j - 1].ix, row[i].kb, row[i].kt};
    const auto found = open->find(key);
    if (found != open->end()) {
      (*prisms)[found->second].iy1 = iy;
      next[key] = found->second;
    } else {
      next[key] = prisms->size();
      prisms->push_back({row[i].ix, row[j - 1].ix, iy, iy, row[i].kb, row[i].kt});
    }
    i = j;
  }
  *open = std::move(next);
}

// Rounds a kept run's band outward to multiples of `step` voxels: its top up; its bottom
// down where it lies above the lowest level a body's band can reach over this column (the
// lowest ground within the ground radius plus the floor band), else it starts at that
// level rounded down (the voxels below that level never meet a body's band, as the runs
// left out whole), so that walls and clutter standing on one floor share their bottoms.
struct BandRounding {
  int32_t step = 1;              // voxels
  double floor_band_voxels = 0;  // MapObstacleOptions::floor_band_m in voxels

  static int32_t Down(int32_t k, int32_t step) {
    return step * static_cast<int32_t>(std::floor(static_cast<double>(k) / step));
  }
  // low: the lowest run top within the ground radius (LowGrid), of a run kept for reaching
  // above low + floor band - 1 voxel.
  Run Round(Run r, int32_t low) const {
    // The ground is at most a voxel below the top of voxel `low`, i.e. no lower than voxel
    // `low`'s bottom; a body's band starts the floor band above its ground.
    const int32_t lowest_band_voxel = static_cast<int32_t>(std::floor(low + floor_band_voxels));
    r.kb = Down(std::max(r.kb, lowest_band_voxel), step);
    r.kt = Down(r.kt, step) + step - 1;
    return r;
  }
};

// The band step in voxels: at least one voxel.
int32_t BandStepVoxels(double band_step_m, double res) {
  const double n = std::floor(band_step_m / res + 1e-9);
  return static_cast<int32_t>(std::max(1.0, std::min(n, 1e6)));
}

// Appends a rounded run (runs arrive by row, column, lowest first), joining it to
// the previous run of the same column when their rounded bands touch.
void AddRounded(const Run& r, std::vector<Run>* row) {
  if (!row->empty() && row->back().ix == r.ix && row->back().iy == r.iy && r.kb <= row->back().kt + 1) {
    row->back().kt = std::max(row->back().kt, r.kt);
    return;
  }
  row->push_back(r);
}

// The runs that may reach a body's band, their bands rounded (BandRounding), sorted by
// (iy, ix, kb) with a column's touching rounded runs joined. A foot stands on a surface
// no lower than a voxel below its top voxel's top, so a run whose top is within the floor
// band of that never reaches the band. Counts the runs kept in *kept_count.
std::vector<Run> KeptRuns(const std::vector<Run>& runs, LowGrid* grid, const MapObstacleOptions& options, double res,
                          int64_t* kept_count) {
  const double band_voxels = options.floor_band_m / res - 1.0;
  const BandRounding rounding{BandStepVoxels(options.band_step_m, res), options.floor_band_m / res};
  std::vector<Run> kept;
  for (const Run& r : runs) {  // sorted by (iy, ix, kb): so are the rounded runs
    const int32_t low = grid->at(r.ix, r.iy);
    if (r.kt - low <= band_voxels) continue;
    ++*kept_count;
    AddRounded(rounding.Round(r, low), &kept);
  }
  return kept;
}

// The runs with x and y swapped, sorted by (iy, ix, kb) again.
std::vector<Run> Transposed(std::vector<Run> runs) {
  for (Run& r : runs) std::swap(r.ix, r.iy);
  std::sort(runs.begin(), runs.end(),
            [](const Run& a, const Run& b) { return std::tie(a.iy, a.ix, a.kb) < std::tie(b.iy, b.ix, b.kb); });
  return runs;
}

// Prisms of the runs (sorted by (iy, ix, kb), one band per cell and level) merged row by
// row (MergeRow); nullopt, saying why, when the deadline passes or there are more than
// max_prisms.
std::optional<std::vector<CellPrism>> MergeRows(const std::vector<Run>& runs, const MapObstacleOptions& options,
                                                std::string* why) {
  std::vector<CellPrism> prisms;
  std::map<SpanKey, size_t> open;
  int32_t previous_iy = INT32_MIN;
  for (size_t i = 0; i < runs.size();) {
    if (options.deadline.Expired()) {
      *why = "the time ran out";
      return std::nullopt;
    }
    const int32_t iy = runs[i].iy;
    std::vector<Run> row;
    for (; i < runs.size() && runs[i].iy == iy; ++i) row.push_back(runs[i]);
    if (previous_iy == INT32_MIN || iy != previous_iy + 1) open.clear();  // a row without runs ends every prism
    previous_iy = iy;
    MergeRow(std::move(row), iy, &open, &prisms);
    if (prisms.size() > options.max_prisms) {
      *why = "more than " + std::to_string(options.max_prisms) + " prisms";
      return std::nullopt;
    }
  }
  return prisms;
}

MapObstacles Incomplete(const std::string& why, Clock::time_point start) {
  MapObstacles out;
  out.complete = false;
  out.message = "no body obstacles from the map: " + why;
  out.time_s = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace

MapObstacles MapBodyObstacles(const OccupancyMap& map, const MapObstacleOptions& options) {
  const Clock::time_point start = Clock::now();
  if (!std::isfinite(options.floor_band_m) || options.floor_band_m < 0.0 || !std::isfinite(options.ground_radius_m) ||
      options.ground_radius_m < 0.0 || !std::isfinite(options.grow_m) || options.grow_m < 0.0) {
    throw InputError("body obstacles from a map: the floor band, the ground radius and the growth must be finite and >= 0 m");
  }
  const double res = map.resolution_m;
  MapObstacles out;
  if (map.leaves.empty() || !std::isfinite(res) || res <= 0.0) return out;
  const uint64_t cells = LeafColumnCells(map);
  if (cells > options.max_leaf_columns) {
    std::ostringstream why;
    why << "its leaves cover " << cells << " column cells, more than the budget of " << options.max_leaf_columns;
    return Incomplete(why.str(), start);
  }
  const std::vector<Run> runs = ColumnRuns(map, cells);
  out.voxel_runs = static_cast<int64_t>(runs.size());
  if (runs.empty()) return out;
  LowGrid grid;
  int32_t x1 = INT32_MIN, y1 = INT32_MIN;
  grid.x0 = grid.y0 = INT32_MAX;
  for (const Run& r : runs) {
    grid.x0 = std::min(grid.x0, r.ix), grid.y0 = std::min(grid.y0, r.iy);
    x1 = std::max(x1, r.ix), y1 = std::max(y1, r.iy);
  }
  const uint64_t nx = static_cast<uint64_t>(x1 - grid.x0) + 1, ny = static_cast<uint64_t>(y1 - grid.y0) + 1;
  if (nx * ny > options.max_grid_cells) {
    std::ostringstream why;
    why << "its plan extent is " << nx << " x " << ny << " cells, more than the budget of " << options.max_grid_cells;
    return Incomplete(why.str(), start);
  }
  grid.nx = static_cast<int32_t>(nx), grid.ny = static_cast<int32_t>(ny);
  grid.low.assign(nx * ny, INT32_MAX);
  for (const Run& r : runs) grid.at(r.ix, r.iy) = std::min(grid.at(r.ix, r.iy), r.kt);
  LowestAround(&grid, static_cast<int32_t>(std::ceil(options.ground_radius_m / res)));
  const std::vector<Run> kept = KeptRuns(runs, &grid, options, res, &out.runs_above_floor);
  if (options.deadline.Expired()) return Incomplete("the time ran out", start);
  // Rows merged along x, then along y; the fewer prisms kept (a wall along y merges along y).
  std::string why;
  std::optional<std::vector<CellPrism>> along_x = MergeRows(kept, options, &why);
  if (!along_x && options.deadline.Expired()) return Incomplete(why, start);
  std::optional<std::vector<CellPrism>> along_y = MergeRows(Transposed(kept), options, &why);
  if (!along_x && !along_y) return Incomplete(why, start);
  if (along_y && (!along_x || along_y->size() < along_x->size())) {
    for (CellPrism& p : *along_y) p = {p.iy0, p.iy1, p.ix0, p.ix1, p.kb, p.kt};
    along_x = std::move(along_y);
  }
  const std::vector<CellPrism>& cell_prisms = *along_x;
  out.prisms.reserve(cell_prisms.size());
  for (const CellPrism& p : cell_prisms) {
    const Eigen::Vector2d grow = Eigen::Vector2d::Constant(options.grow_m);
    out.prisms.push_back({Eigen::Vector2d(p.ix0 * res, p.iy0 * res) - grow,
                          Eigen::Vector2d((p.ix1 + 1) * res, (p.iy1 + 1) * res) + grow, p.kb * res, (p.kt + 1) * res});
  }
  out.time_s = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace mfp
