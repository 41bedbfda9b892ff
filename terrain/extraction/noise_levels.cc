#include "terrain/extraction/internal/noise_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "terrain/extraction/internal/parallel_work.h"

namespace mfp {
namespace {

// The median of the seen heights of the cell's 3 x 3 neighbourhood (itself included) when
// it may lie half a voxel or more from the cell's own height; NaN with fewer than 5 seen,
// and when the median lies nearer (the only medians OffCellsInRows keeps are the others).
// The distance from the cell's height falls as the height rises, so the heights half a
// voxel or more below it come first in order and those as far above it last: the median
// (the n/2-th of n in order) is one of them only when more than n/2, or at least n - n/2,
// are; otherwise it is near and not computed.
float FarNeighbourhoodMedian(const HeightMap& hm, int cell) {
  float seen[9];
  int n = 0, below = 0, above = 0;
  const int row = cell / hm.cols, col = cell % hm.cols;
  const double own = hm.height_m[static_cast<size_t>(cell)], half = 0.5 * hm.resolution_m;
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (!hm.Inside(row + dr, col + dc)) continue;
      const float h = hm.height_m[static_cast<size_t>(hm.Index(row + dr, col + dc))];
      if (std::isnan(h)) continue;
      seen[n++] = h;
      const double d = own - h;  // OffCellsInRows' difference, were h the median
      below += d >= half;
      above += d <= -half;
    }
  }
  if (n < 5 || (below <= n / 2 && above < n - n / 2)) return NAN;
  std::nth_element(seen, seen + n / 2, seen + n);
  return seen[n / 2];
}

// The surface cells [begin, end) (ascending) off their neighbourhood, in order, appended
// to off.
void OffCellsAmong(const HeightMap& hm, double tolerance_m, const int* begin, const int* end,
                   std::vector<OffCell>* off) {
  for (const int* it = begin; it != end; ++it) {
    const int cell = *it;
    const float median = FarNeighbourhoodMedian(hm, cell);
    const double d = static_cast<double>(hm.height_m[static_cast<size_t>(cell)]) - median;
    if (std::isnan(d) || std::abs(d) < 0.5 * hm.resolution_m || std::abs(d) > tolerance_m) continue;
    off->push_back({cell, static_cast<int8_t>(d > 0.0 ? 1 : -1), median});
  }
}

// The entry of `cell` in off, or -1.
int FindOff(const std::vector<OffCell>& off, int cell) {
  const auto it = std::lower_bound(off.begin(), off.end(), cell, [](const OffCell& o, int c) { return o.cell < c; });
  return it != off.end() && it->cell == cell ? static_cast<int>(it - off.begin()) : -1;
}

// Whether a group of cells off their neighbourhood on `side` stands alone: every seen cell
// around it lies at least half a voxel beyond the group on the other side (a bump above
// all around it, a pit below). A corner of a voxelised tilt's staircase has cells of its
// own level or beyond beside it, so it is not noise.
bool Isolated(const HeightMap& hm, const std::vector<int>& group, int side) {
  float lo = INFINITY, hi = -INFINITY;
  for (int cell : group) {
    lo = std::min(lo, hm.height_m[static_cast<size_t>(cell)]);
    hi = std::max(hi, hm.height_m[static_cast<size_t>(cell)]);
  }
  const double half = 0.5 * hm.resolution_m;
  for (int cell : group) {
    const int row = cell / hm.cols, col = cell % hm.cols;
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if (!hm.Inside(row + dr, col + dc)) continue;
        const int nb = hm.Index(row + dr, col + dc);
        const float h = hm.height_m[static_cast<size_t>(nb)];
        if (std::isnan(h) || std::find(group.begin(), group.end(), nb) != group.end()) continue;
        if (side > 0 ? h > lo - half : h < hi + half) return false;
      }
    }
  }
  return true;
}

}  // namespace

NoiseLevels NoiseFreeLevels(const HeightMap& hm, const std::vector<int>& surface_cells, double tolerance_m,
                            int max_cells) {
  std::vector<OffCell> off;
  OffCellsAmong(hm, tolerance_m, surface_cells.data(), surface_cells.data() + surface_cells.size(), &off);
  return NoiseFreeLevelsFrom(hm, off, max_cells);
}

std::vector<std::vector<OffCell>> OffCellsOfLayers(const std::vector<HeightMap>& layers,
                                                   const std::vector<SurfaceAnalysis>& surfaces, double tolerance_m,
                                                   int threads) {
  // Bands of BandRows rows (parallel_work.h): enough to share one large layer between threads.
  struct Band {
    size_t layer;
    int r0, r1;
    std::vector<OffCell> off;
  };
  std::vector<Band> bands;
  for (size_t l = 0; l < layers.size(); ++l) {
    const int band_rows = BandRows(layers[l].cols);
    for (int r0 = 0; r0 < layers[l].rows; r0 += band_rows) bands.push_back({l, r0, std::min(layers[l].rows, r0 + band_rows), {}});
  }
  ParallelFor(static_cast<int>(bands.size()), threads, [&](int i) {
    Band& band = bands[static_cast<size_t>(i)];
    // The band's surface cells: those in [r0 * cols, r1 * cols) of the layer's ascending list.
    const std::vector<int>& cells = surfaces[band.layer].cells;
    const int cols = layers[band.layer].cols;
    const int* begin = std::lower_bound(cells.data(), cells.data() + cells.size(), band.r0 * cols);
    const int* end = std::lower_bound(begin, cells.data() + cells.size(), band.r1 * cols);
    OffCellsAmong(layers[band.layer], tolerance_m, begin, end, &band.off);
  });
  std::vector<std::vector<OffCell>> off(layers.size());
  for (const Band& band : bands) off[band.layer].insert(off[band.layer].end(), band.off.begin(), band.off.end());
  return off;
}

NoiseLevels NoiseFreeLevelsFrom(const HeightMap& hm, const std::vector<OffCell>& off, int max_cells) {
  NoiseLevels out;
  // 8-connected groups of off cells on one side, each from its lowest cell, in order.
  std::vector<uint8_t> visited(off.size(), 0);
  std::vector<int> group, entries;
  for (size_t start = 0; start < off.size(); ++start) {
    if (visited[start]) continue;
    const int8_t side = off[start].side;
    group.assign(1, off[start].cell);
    entries.assign(1, static_cast<int>(start));
    visited[start] = 1;
    for (size_t next = 0; next < group.size(); ++next) {
      const int row = group[next] / hm.cols, col = group[next] % hm.cols;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (!hm.Inside(row + dr, col + dc)) continue;
          const int e = FindOff(off, hm.Index(row + dr, col + dc));
          if (e < 0 || visited[static_cast<size_t>(e)] || off[static_cast<size_t>(e)].side != side) continue;
          visited[static_cast<size_t>(e)] = 1;
          group.push_back(off[static_cast<size_t>(e)].cell);
          entries.push_back(e);
        }
      }
    }
    if (static_cast<int>(group.size()) > max_cells || !Isolated(hm, group, side)) continue;
    if (out.denoised_cells == 0) {
      out.levels = hm;
      out.denoised.assign(hm.height_m.size(), 0);
    }
    for (int e : entries) {
      const OffCell& o = off[static_cast<size_t>(e)];
      out.levels.height_m[static_cast<size_t>(o.cell)] = o.median;
      out.denoised[static_cast<size_t>(o.cell)] = 1;
      ++out.denoised_cells;
    }
  }
  return out;
}

bool FlatLevel(const HeightMap& levels, int cell) {
  const int row = cell / levels.cols, col = cell % levels.cols;
  const float h = levels.height_m[static_cast<size_t>(cell)];
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (!levels.Inside(row + dr, col + dc)) return false;
      const float nb = levels.height_m[static_cast<size_t>(levels.Index(row + dr, col + dc))];
      if (!(std::abs(nb - h) < 0.5 * levels.resolution_m)) return false;
    }
  }
  return true;
}

}  // namespace mfp
