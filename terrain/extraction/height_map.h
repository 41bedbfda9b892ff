#pragma once
// A 2.5-D height map of the top surfaces of an occupancy map: for each grid cell (on the
// octree's x-y grid) the highest top face of any occupied leaf above it. Plus the local
// surface analysis the segmentation starts from: a plane fit per cell over a window at
// least a foot wide, giving a normal and a roughness. Plain Eigen.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "base/deadline.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

struct HeightMap {
  double resolution_m = 0.0;                                 // cell edge [m]
  Eigen::Vector2d origin_world_m = Eigen::Vector2d::Zero();  // lower corner of cell (0, 0) [m]
  int rows = 0;                                              // cells along y
  int cols = 0;                                              // cells along x
  std::vector<float> height_m;  // row-major (row = y index); NaN where nothing is occupied

  int Index(int row, int col) const { return row * cols + col; }
  bool Inside(int row, int col) const { return row >= 0 && row < rows && col >= 0 && col < cols; }
  bool HasSurface(int row, int col) const;
  Eigen::Vector2d CellCenter(int row, int col) const;
};

// Largest height map built by default: 4096 x 4096 cells.
constexpr size_t kDefaultMaxHeightMapCells = size_t{4096} * 4096;

// Throws InputError when the map's resolution is not positive and finite, a leaf is not
// a finite cube of resolution * 2^k on the grid, or the occupied x-y extent needs more
// than max_cells cells. An empty map gives a 0 x 0 height map.
HeightMap BuildHeightMap(const OccupancyMap& map,
                         size_t max_cells = kDefaultMaxHeightMapCells);

// BuildHeightMap's grid (resolution, origin, rows, cols) with every cell NaN: its checks,
// throws and limits, without the pass that expands each leaf into its cells' heights. The
// leaves' bounds are taken in `threads` parts at once (the same grid for any count).
HeightMap HeightMapGrid(const OccupancyMap& map, size_t max_cells = kDefaultMaxHeightMapCells, int threads = 1);

// The local fit of the surface cells only (a layer of a large grid holds few of them).
struct SurfaceAnalysis {
  std::vector<int> cells;                     // the surface cells (height not NaN), ascending
  std::vector<Eigen::Vector3f> normal_world;  // per entry of cells, upward unit normal; NaN if unknown
  std::vector<float> roughness_m;             // per entry of cells, RMS residual of the fit; inf if unknown
  bool stopped = false;  // the deadline ended the analysis; cells not reached are unknown

  // The entry of `cell` in cells, or -1 when it has no surface.
  int Find(int cell) const;
  // The cell's normal (NaN if unknown or no surface) and roughness (inf likewise).
  Eigen::Vector3f NormalAt(int cell) const;
  float RoughnessAt(int cell) const;
};

// Fits z = a x + b y + c around each cell over a (2 w + 1)^2 window, w = window_half_cells.
// Neighbours whose height differs from the centre by more than
// step_gate_m + (distance * tan(max_slope_rad)) are left out, so a cell beside a step
// still gets the normal of its own surface.
// The work is (surface cells) * (2 w + 1)^2 neighbour visits (FitWork); the deadline is
// checked every row.
SurfaceAnalysis AnalyzeSurface(const HeightMap& height_map, int window_half_cells,
                               double step_gate_m, double max_slope_rad,
                               const Deadline& deadline = Deadline());
double FitWork(size_t surface_cells, int window_half_cells);

// AnalyzeSurface in parts (each cell's fit is its own, so parts may run at once): the
// surface cells with unknown fits, then the fits of entries [begin, end) of its cells;
// false when the deadline stopped a part (its entries from that row on stay unknown).
SurfaceAnalysis SurfaceCellsOf(const HeightMap& height_map);
bool FitSurfaceCells(const HeightMap& height_map, int window_half_cells, double step_gate_m, double max_slope_rad,
                     const Deadline& deadline, size_t begin, size_t end, SurfaceAnalysis* analysis);

}  // namespace mfp
