#include "terrain/extraction/internal/noise_levels.h"

#include <algorithm>
#include <cmath>

namespace mfp {
namespace {

// The median of the seen heights of the cell's 3 x 3 neighbourhood (NaN with fewer than 5).
float NeighbourhoodMedian(const HeightMap& hm, int cell) {
  float seen[9];
  int n = 0;
  const int row = cell / hm.cols, col = cell % hm.cols;
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (!hm.Inside(row + dr, col + dc)) continue;
      const float h = hm.height_m[static_cast<size_t>(hm.Index(row + dr, col + dc))];
      if (!std::isnan(h)) seen[n++] = h;
    }
  }
  if (n < 5) return NAN;
  std::nth_element(seen, seen + n / 2, seen + n);
  return seen[n / 2];
}

// Per cell: +1 or -1 when one voxel (up to the tolerance) above or below its
// neighbourhood's median, else 0.
std::vector<int8_t> OffSides(const HeightMap& hm, const std::vector<float>& median, double tolerance_m) {
  std::vector<int8_t> side(hm.height_m.size(), 0);
  for (size_t cell = 0; cell < side.size(); ++cell) {
    const double d = static_cast<double>(hm.height_m[cell]) - median[cell];
    if (std::isnan(d) || std::abs(d) < 0.5 * hm.resolution_m || std::abs(d) > tolerance_m) continue;
    side[cell] = d > 0.0 ? 1 : -1;
  }
  return side;
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

NoiseLevels NoiseFreeLevels(const HeightMap& hm, double tolerance_m, int max_cells) {
  NoiseLevels out;
  out.levels = hm;
  out.denoised.assign(hm.height_m.size(), 0);
  std::vector<float> median(hm.height_m.size(), NAN);
  for (int cell = 0; cell < static_cast<int>(median.size()); ++cell) {
    if (!std::isnan(hm.height_m[static_cast<size_t>(cell)])) median[static_cast<size_t>(cell)] = NeighbourhoodMedian(hm, cell);
  }
  const std::vector<int8_t> side = OffSides(hm, median, tolerance_m);
  std::vector<uint8_t> visited(side.size(), 0);
  std::vector<int> group;
  for (int start = 0; start < static_cast<int>(side.size()); ++start) {
    if (side[static_cast<size_t>(start)] == 0 || visited[static_cast<size_t>(start)]) continue;
    group.assign(1, start);
    visited[static_cast<size_t>(start)] = 1;
    for (size_t next = 0; next < group.size(); ++next) {
      const int row = group[next] / hm.cols, col = group[next] % hm.cols;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (!hm.Inside(row + dr, col + dc)) continue;
          const int nb = hm.Index(row + dr, col + dc);
          if (visited[static_cast<size_t>(nb)] || side[static_cast<size_t>(nb)] != side[static_cast<size_t>(start)]) continue;
          visited[static_cast<size_t>(nb)] = 1;
          group.push_back(nb);
        }
      }
    }
    if (static_cast<int>(group.size()) > max_cells || !Isolated(hm, group, side[static_cast<size_t>(start)])) continue;
    for (int cell : group) {
      out.levels.height_m[static_cast<size_t>(cell)] = median[static_cast<size_t>(cell)];
      out.denoised[static_cast<size_t>(cell)] = 1;
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
