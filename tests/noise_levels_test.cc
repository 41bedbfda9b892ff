#include "terrain/extraction/internal/noise_levels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace mfp {
namespace {

// The off cells by their definition: every surface cell's 3 x 3 median (of at least 5 seen
// heights) taken, the cell kept when it lies at least half a voxel and at most the
// tolerance from it.
std::vector<OffCell> OffCellsByDefinition(const HeightMap& hm, double tolerance_m) {
  std::vector<OffCell> off;
  for (int cell = 0; cell < hm.rows * hm.cols; ++cell) {
    const float own = hm.height_m[static_cast<size_t>(cell)];
    if (std::isnan(own)) continue;
    std::vector<float> seen;
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int r = cell / hm.cols + dr, c = cell % hm.cols + dc;
        if (!hm.Inside(r, c) || std::isnan(hm.height_m[static_cast<size_t>(hm.Index(r, c))])) continue;
        seen.push_back(hm.height_m[static_cast<size_t>(hm.Index(r, c))]);
      }
    }
    if (seen.size() < 5) continue;
    std::sort(seen.begin(), seen.end());
    const float median = seen[seen.size() / 2];
    const double d = static_cast<double>(own) - median;
    if (std::abs(d) < 0.5 * hm.resolution_m || std::abs(d) > tolerance_m) continue;
    off.push_back({cell, static_cast<int8_t>(d > 0.0 ? 1 : -1), median});
  }
  return off;
}

// A floor of whole voxels with steps, single-voxel noise, near-half-voxel offsets and holes.
HeightMap NoisyFloor(std::mt19937* rng, int rows, int cols, double res) {
  HeightMap hm;
  hm.rows = rows;
  hm.cols = cols;
  hm.resolution_m = res;
  hm.height_m.assign(static_cast<size_t>(rows) * cols, NAN);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double p = u(*rng);
      if (p < 0.15) continue;  // a hole
      double voxels = (c > cols / 2 ? 3 : 0) + (r > rows / 3 ? 1 : 0);
      if (p < 0.35) voxels += u(*rng) < 0.5 ? 1 : -1;  // one voxel off
      if (p > 0.97) voxels += u(*rng) < 0.5 ? 0.5 : -0.49;  // about half a voxel off
      if (p > 0.99) voxels += 4;  // a drop
      hm.height_m[static_cast<size_t>(hm.Index(r, c))] = static_cast<float>(voxels * res);
    }
  }
  return hm;
}

TEST(NoiseLevels, OffCellsAreThoseOfEveryCellsMedian) {
  std::mt19937 rng(7);
  for (const double res : {0.02, 0.05, 0.1}) {
    std::vector<HeightMap> layers;
    for (int k = 0; k < 3; ++k) layers.push_back(NoisyFloor(&rng, 40 + 7 * k, 55 - 5 * k, res));
    for (const double tolerance : {0.6 * res, 1.5 * res, 10 * res}) {
      for (const int threads : {1, 2, 3}) {
        std::vector<SurfaceAnalysis> surfaces;
        for (const HeightMap& layer : layers) surfaces.push_back(SurfaceCellsOf(layer));
        const std::vector<std::vector<OffCell>> off = OffCellsOfLayers(layers, surfaces, tolerance, threads);
        ASSERT_EQ(off.size(), layers.size());
        for (size_t l = 0; l < layers.size(); ++l) {
          const std::vector<OffCell> expected = OffCellsByDefinition(layers[l], tolerance);
          ASSERT_EQ(off[l].size(), expected.size()) << "res " << res << " tolerance " << tolerance;
          ASSERT_FALSE(expected.empty());
          for (size_t i = 0; i < expected.size(); ++i) {
            EXPECT_EQ(off[l][i].cell, expected[i].cell);
            EXPECT_EQ(off[l][i].side, expected[i].side);
            EXPECT_EQ(off[l][i].median, expected[i].median);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace mfp
