#include "bench/coverage_breakdown.h"

#include <cmath>
#include <cstdio>

namespace mfp {

int FateUnder(const Eigen::Vector3d& point, const RegionExtractionResult& result) {
  const HeightMap& grid = result.layers.front();
  const double res = grid.resolution_m;
  const int col = static_cast<int>(std::floor((point.x() - grid.origin_world_m.x()) / res));
  const int row = static_cast<int>(std::floor((point.y() - grid.origin_world_m.y()) / res));
  if (!grid.Inside(row, col)) return -1;
  const int cell = grid.Index(row, col);
  int fate = -1;
  for (size_t l = 0; l < result.layers.size(); ++l) {
    const float h = result.layers[l].height_m[static_cast<size_t>(cell)];
    const CellFate f = result.cell_fates[l][static_cast<size_t>(cell)];
    const bool here = std::isnan(h) ? f != CellFate::kNoSurface : std::abs(h - point.z()) <= res + 1e-6;
    // Of several layers there, the one that got furthest (covered beats inset beats dropped).
    if (here && static_cast<int>(f) > fate) fate = static_cast<int>(f);
  }
  return fate;
}

CoverageBreakdown BreakDownMissedFloor(const VoxelQuality& quality, const RegionExtractionResult& result) {
  CoverageBreakdown b;
  b.certifiable = quality.certifiable_floor_cells;
  b.missed = static_cast<int>(quality.missed_certifiable.size());
  if (result.layers.empty() || result.cell_fates.size() != result.layers.size()) return b;
  for (const Eigen::Vector3d& p : quality.missed_certifiable) {
    const int fate = FateUnder(p, result);
    if (fate < 0) {
      ++b.no_layer_surface;
    } else {
      ++b.by_fate[static_cast<size_t>(fate)];
    }
  }
  return b;
}

void PrintBreakdownHeader() {
  std::printf("%-22s %9s %7s %8s", "scan", "cert_cells", "missed", "no_layer");
  for (int f = 1; f < kCellFateCount; ++f) {
    const CellFate fate = static_cast<CellFate>(f);
    std::printf(" %15s", fate == CellFate::kCovered ? "off_height" : CellFateName(fate));
  }
  std::printf("\n");
}

void PrintBreakdownRow(const std::string& name, const CoverageBreakdown& b) {
  const double to_pct = b.certifiable > 0 ? 100.0 / b.certifiable : 0.0;
  std::printf("%-22s %9d %6.1f%% %7.1f%%", name.c_str(), b.certifiable, b.missed * to_pct, b.no_layer_surface * to_pct);
  for (int f = 1; f < kCellFateCount; ++f) std::printf(" %14.1f%%", b.by_fate[static_cast<size_t>(f)] * to_pct);
  std::printf("\n");
}

}  // namespace mfp
