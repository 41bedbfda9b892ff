#include "terrain/extraction/height_map.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "base/check.h"
#include "base/round.h"
#include "terrain/extraction/internal/parallel_work.h"

namespace mfp {

bool HeightMap::HasSurface(int row, int col) const {
  return Inside(row, col) && !std::isnan(height_m[static_cast<size_t>(Index(row, col))]);
}

Eigen::Vector2d HeightMap::CellCenter(int row, int col) const {
  return origin_world_m + resolution_m * Eigen::Vector2d(col + 0.5, row + 0.5);
}

HeightMap HeightMapGrid(const OccupancyMap& map, size_t max_cells, int threads) {
  const double res = map.resolution_m;
  if (!std::isfinite(res) || res <= 0.0) {
    throw InputError("occupancy map resolution must be a finite number > 0 m");
  }
  HeightMap hm;
  hm.resolution_m = res;
  if (map.leaves.empty()) return hm;
  // Integer cell bounds of every leaf; leaves are aligned to the grid at multiples of res.
  struct Bounds {
    long long lo_x = std::numeric_limits<long long>::max(), lo_y = lo_x;
    long long hi_x = std::numeric_limits<long long>::min(), hi_y = hi_x;
  };
  const int parts = std::max(1, threads);
  std::vector<Bounds> part_bounds(static_cast<size_t>(parts));
  ParallelFor(parts, threads, [&](int p) {
    const size_t n_leaves = map.leaves.size(), k = static_cast<size_t>(p), m = static_cast<size_t>(parts);
    Bounds& b = part_bounds[k];
    const double max_coord_m = 1e6;
    for (size_t i = n_leaves * k / m; i < n_leaves * (k + 1) / m; ++i) {
      const OccupiedLeaf& leaf = map.leaves[i];
      const double cells = leaf.size_m / res;
      if (!leaf.center_world_m.allFinite() || !std::isfinite(cells) || cells < 0.5 ||
          cells > 65536.5 || leaf.center_world_m.cwiseAbs().maxCoeff() > max_coord_m) {
        throw InputError("occupancy map: a leaf is not a finite cube between one voxel and the "
                         "octree's extent");
      }
      const long long n = RoundToLongLong(cells);
      const long long x0 = RoundToLongLong((leaf.center_world_m.x() - 0.5 * leaf.size_m) / res);
      const long long y0 = RoundToLongLong((leaf.center_world_m.y() - 0.5 * leaf.size_m) / res);
      b.lo_x = std::min(b.lo_x, x0);
      b.lo_y = std::min(b.lo_y, y0);
      b.hi_x = std::max(b.hi_x, x0 + n);
      b.hi_y = std::max(b.hi_y, y0 + n);
    }
  });
  long long lo_x = std::numeric_limits<long long>::max(), lo_y = lo_x;
  long long hi_x = std::numeric_limits<long long>::min(), hi_y = hi_x;
  for (const Bounds& b : part_bounds) {
    lo_x = std::min(lo_x, b.lo_x);
    lo_y = std::min(lo_y, b.lo_y);
    hi_x = std::max(hi_x, b.hi_x);
    hi_y = std::max(hi_y, b.hi_y);
  }
  const double cells = static_cast<double>(hi_x - lo_x) * static_cast<double>(hi_y - lo_y);
  if (cells > static_cast<double>(max_cells)) {
    std::ostringstream msg;
    msg << "occupancy map: the occupied area is " << (hi_x - lo_x) * res << " m x "
        << (hi_y - lo_y) * res << " m, more than the height map limit of " << max_cells
        << " cells at " << res << " m";
    throw InputError(msg.str());
  }
  hm.cols = static_cast<int>(hi_x - lo_x);
  hm.rows = static_cast<int>(hi_y - lo_y);
  hm.origin_world_m = Eigen::Vector2d(lo_x * res, lo_y * res);
  hm.height_m.assign(static_cast<size_t>(hm.rows) * hm.cols,
                     std::numeric_limits<float>::quiet_NaN());
  return hm;
}

HeightMap BuildHeightMap(const OccupancyMap& map, size_t max_cells) {
  HeightMap hm = HeightMapGrid(map, max_cells);
  const double res = hm.resolution_m;
  const long long lo_x = RoundToLongLong(hm.origin_world_m.x() / res);
  const long long lo_y = RoundToLongLong(hm.origin_world_m.y() / res);
  for (const OccupiedLeaf& leaf : map.leaves) {
    const int n = static_cast<int>(RoundToLongLong(leaf.size_m / res));
    const int c0 =
        static_cast<int>(RoundToLongLong((leaf.center_world_m.x() - 0.5 * leaf.size_m) / res) - lo_x);
    const int r0 =
        static_cast<int>(RoundToLongLong((leaf.center_world_m.y() - 0.5 * leaf.size_m) / res) - lo_y);
    const float top = static_cast<float>(leaf.center_world_m.z() + 0.5 * leaf.size_m);
    for (int r = r0; r < r0 + n; ++r) {
      float* row = &hm.height_m[static_cast<size_t>(r) * hm.cols];
      for (int c = c0; c < c0 + n; ++c) {
        if (!(row[c] >= top)) row[c] = top;  // NaN compares false: first leaf wins
      }
    }
  }
  return hm;
}

int SurfaceAnalysis::Find(int cell) const {
  const auto it = std::lower_bound(cells.begin(), cells.end(), cell);
  return it != cells.end() && *it == cell ? static_cast<int>(it - cells.begin()) : -1;
}

Eigen::Vector3f SurfaceAnalysis::NormalAt(int cell) const {
  const int entry = Find(cell);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  return entry < 0 ? Eigen::Vector3f(nan, nan, nan) : normal_world[static_cast<size_t>(entry)];
}

float SurfaceAnalysis::RoughnessAt(int cell) const {
  const int entry = Find(cell);
  return entry < 0 ? std::numeric_limits<float>::infinity() : roughness_m[static_cast<size_t>(entry)];
}

double FitWork(size_t surface_cells, int window_half_cells) {
  const double side = 2.0 * window_half_cells + 1.0;
  return static_cast<double>(surface_cells) * side * side;
}

SurfaceAnalysis SurfaceCellsOf(const HeightMap& hm) {
  SurfaceAnalysis out;
  // Blocks of cells with no surface (most of a layer above the ground) are passed over by
  // one test each.
  constexpr size_t kBlock = 16;
  const size_t n = hm.height_m.size();
  const float* h = hm.height_m.data();
  for (size_t b = 0; b < n; b += kBlock) {
    const size_t e = std::min(n, b + kBlock);
    uint8_t any = 0;
    for (size_t i = b; i < e; ++i) any |= static_cast<uint8_t>(!std::isnan(h[i]));
    if (!any) continue;
    for (size_t i = b; i < e; ++i) {
      if (!std::isnan(h[i])) out.cells.push_back(static_cast<int>(i));
    }
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.normal_world.assign(out.cells.size(), Eigen::Vector3f(nan, nan, nan));
  out.roughness_m.assign(out.cells.size(), std::numeric_limits<float>::infinity());
  return out;
}

bool FitSurfaceCells(const HeightMap& hm, int window_half_cells, double step_gate_m, double max_slope_rad,
                     const Deadline& deadline, size_t begin, size_t end, SurfaceAnalysis* analysis) {
  MFP_CHECK(window_half_cells >= 1 && begin <= end && end <= analysis->cells.size());
  SurfaceAnalysis& out = *analysis;
  const double res = hm.resolution_m;
  const double tan_slope = std::tan(max_slope_rad);
  const int w = window_half_cells;
  // Per window offset, the largest height difference a neighbour on the surface may have.
  const int side = 2 * w + 1;
  std::vector<double> gate(static_cast<size_t>(side) * side);
  for (int dr = -w; dr <= w; ++dr) {
    for (int dc = -w; dc <= w; ++dc) {
      const double dist_m = res * std::sqrt(double(dr * dr + dc * dc));
      gate[static_cast<size_t>((dr + w) * side + (dc + w))] = step_gate_m + dist_m * tan_slope;
    }
  }
  int row_checked = -1;  // the deadline is checked once per row holding a surface cell
  for (size_t entry = begin; entry < end; ++entry) {
    const int r = out.cells[entry] / hm.cols, c = out.cells[entry] % hm.cols;
    if (r != row_checked) {
      row_checked = r;
      if (deadline.Expired()) return false;
    }
    const float hc = hm.height_m[static_cast<size_t>(out.cells[entry])];
    // Least squares in coordinates relative to the cell (x, y in cells, z in m): the
    // rows (dc, dr, 1) of A summed into A^T A (small integers, exact in any order) and
    // A^T z.
    long long sxx = 0, sxy = 0, syy = 0, sx = 0, sy = 0, count = 0;
    Eigen::Vector3d Atz = Eigen::Vector3d::Zero();
    double zz = 0.0;
    for (int dr = -w; dr <= w; ++dr) {
      if (r + dr < 0 || r + dr >= hm.rows) continue;
      for (int dc = -w; dc <= w; ++dc) {
        if (c + dc < 0 || c + dc >= hm.cols) continue;
        const float h = hm.height_m[static_cast<size_t>(hm.Index(r + dr, c + dc))];
        if (std::isnan(h)) continue;
        const double dz = h - hc;
        if (std::abs(dz) > gate[static_cast<size_t>((dr + w) * side + (dc + w))]) continue;
        sxx += dc * dc;
        sxy += dc * dr;
        syy += dr * dr;
        sx += dc;
        sy += dr;
        Atz += Eigen::Vector3d(dc, dr, 1.0) * dz;
        zz += dz * dz;
        ++count;
      }
    }
    if (count < 3) continue;
    Eigen::Matrix3d AtA;
    AtA << sxx, sxy, sx, sxy, syy, sy, sx, sy, count;
    Eigen::LDLT<Eigen::Matrix3d> ldlt(AtA);
    if (ldlt.info() != Eigen::Success || std::abs(AtA.determinant()) < 1e-9) continue;
    const Eigen::Vector3d p = ldlt.solve(Atz);
    // Sum of squared residuals = z.z - p.(A^T z) for the least-squares solution.
    const double sse = std::max(0.0, zz - p.dot(Atz));
    out.normal_world[entry] = Eigen::Vector3d(-p.x() / res, -p.y() / res, 1.0).normalized().cast<float>();
    out.roughness_m[entry] = static_cast<float>(std::sqrt(sse / count));
  }
  return true;
}

SurfaceAnalysis AnalyzeSurface(const HeightMap& hm, int window_half_cells, double step_gate_m,
                               double max_slope_rad, const Deadline& deadline) {
  SurfaceAnalysis out = SurfaceCellsOf(hm);
  out.stopped = !FitSurfaceCells(hm, window_half_cells, step_gate_m, max_slope_rad, deadline, 0, out.cells.size(), &out);
  return out;
}

}  // namespace mfp
