// Height map, local surface fits and the rectangle cover, with hand-worked answers.
#include "terrain/extraction/height_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "terrain/extraction/internal/rectangle_cover.h"

namespace mfp {
namespace {

TEST(HeightMapTest, PrunedLeavesCoverSeveralCellsAndTheHighestTopWins) {
  OccupancyMap map;
  map.resolution_m = 0.1;
  map.leaves.push_back({Eigen::Vector3d(0.1, 0.1, 0.1), 0.2});   // 2 x 2 cells, top 0.2
  map.leaves.push_back({Eigen::Vector3d(0.05, 0.05, 0.45), 0.1});  // one cell, top 0.5
  map.leaves.push_back({Eigen::Vector3d(0.35, 0.05, -0.05), 0.1}); // one cell, top 0.0
  const HeightMap hm = BuildHeightMap(map);
  EXPECT_EQ(hm.cols, 4);
  EXPECT_EQ(hm.rows, 2);
  EXPECT_NEAR(hm.origin_world_m.x(), 0.0, 1e-12);
  EXPECT_FLOAT_EQ(hm.height_m[hm.Index(0, 0)], 0.5f);
  EXPECT_FLOAT_EQ(hm.height_m[hm.Index(1, 1)], 0.2f);
  EXPECT_FLOAT_EQ(hm.height_m[hm.Index(0, 3)], 0.0f);
  EXPECT_FALSE(hm.HasSurface(0, 2));
  EXPECT_FALSE(hm.HasSurface(1, 3));
}

TEST(HeightMapTest, EmptyMapGivesAnEmptyHeightMap) {
  OccupancyMap map;
  map.resolution_m = 0.02;
  const HeightMap hm = BuildHeightMap(map);
  EXPECT_EQ(hm.rows * hm.cols, 0);
}

TEST(HeightMapTest, RejectsExtentsBeyondTheCellLimit) {
  OccupancyMap map;
  map.resolution_m = 0.02;
  map.leaves.push_back({Eigen::Vector3d(0.01, 0.01, 0.01), 0.02});
  map.leaves.push_back({Eigen::Vector3d(100.01, 100.01, 0.01), 0.02});
  EXPECT_THROW(BuildHeightMap(map, 1000), InputError);
  map.leaves.push_back({Eigen::Vector3d(NAN, 0, 0), 0.02});
  EXPECT_THROW(BuildHeightMap(map), InputError);
}

// The layers' grid: BuildHeightMap's extent with every cell empty, its leaves' bounds
// taken on any number of threads, the same refusals.
TEST(HeightMapTest, TheGridAloneHasTheHeightMapsExtentOnAnyThreadsAndItsRefusals) {
  OccupancyMap map;
  map.resolution_m = 0.1;
  for (int k = 0; k < 37; ++k) map.leaves.push_back({Eigen::Vector3d(0.05 + 0.1 * (k % 7), -0.35 + 0.2 * k, 0.05), 0.1});
  map.leaves.push_back({Eigen::Vector3d(-0.4, 0.2, 1.0), 0.4});  // 4 x 4 cells, the lowest x
  const HeightMap full = BuildHeightMap(map);
  for (int threads : {1, 2, 3, 8}) {
    const HeightMap grid = HeightMapGrid(map, kDefaultMaxHeightMapCells, threads);
    EXPECT_EQ(grid.rows, full.rows) << threads;
    EXPECT_EQ(grid.cols, full.cols) << threads;
    EXPECT_EQ(grid.origin_world_m, full.origin_world_m) << threads;
    EXPECT_EQ(grid.resolution_m, full.resolution_m) << threads;
    ASSERT_EQ(grid.height_m.size(), full.height_m.size()) << threads;
    EXPECT_TRUE(std::all_of(grid.height_m.begin(), grid.height_m.end(), [](float h) { return std::isnan(h); }));
  }
  EXPECT_EQ(full.cols, 13);  // x from -0.6 to 0.7 m
  EXPECT_THROW(HeightMapGrid(map, 100, 2), InputError);
  map.leaves.push_back({Eigen::Vector3d(0, NAN, 0), 0.1});
  for (int threads : {1, 3}) EXPECT_THROW(HeightMapGrid(map, kDefaultMaxHeightMapCells, threads), InputError);
  OccupancyMap empty;
  empty.resolution_m = 0.1;
  EXPECT_EQ(HeightMapGrid(empty, kDefaultMaxHeightMapCells, 2).rows, 0);
}

TEST(HeightMapTest, LocalFitRecoversATiltAndIgnoresAStepBeside) {
  HeightMap hm;
  hm.resolution_m = 0.1;
  hm.rows = 5;
  hm.cols = 5;
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < 5; ++c) {
      // z = 0.05 x, and a 1 m step for columns >= 3.
      hm.height_m.push_back(static_cast<float>(0.05 * hm.CellCenter(r, c).x() + (c >= 3 ? 1.0 : 0.0)));
    }
  }
  const SurfaceAnalysis s = AnalyzeSurface(hm, 1, 0.05, 0.5);
  const Eigen::Vector3f n = s.NormalAt(hm.Index(2, 2));
  EXPECT_NEAR(std::atan2(-n.x(), n.z()), std::atan(0.05), 1e-4);
  EXPECT_NEAR(s.RoughnessAt(hm.Index(2, 2)), 0.0, 1e-6);
  EXPECT_EQ(s.cells.size(), hm.height_m.size());  // every cell has a surface
}

TEST(RectangleCoverTest, LargestRectangleOfAnLShape) {
  // 1 1 0
  // 1 1 0
  // 1 1 1
  // 1 1 1      rows 0..3 top to bottom in memory order
  const std::vector<uint8_t> mask = {1, 1, 0, 1, 1, 0, 1, 1, 1, 1, 1, 1};
  const CellRect best = LargestRectangle(mask, 4, 3);
  EXPECT_EQ(best.Area(), 8);
  EXPECT_EQ(best.cols, 2);
  RectangleCoverOptions options;
  options.target_coverage = 1.0;
  const std::vector<CellRect> cover = GreedyRectangleCover(mask, 4, 3, options);
  ASSERT_EQ(cover.size(), 2u);
  // The second rectangle is grown over covered cells: the whole bottom 2 x 3 block.
  EXPECT_EQ(cover[1].Area(), 6);
}

// A floor cut by a wall with an opening at one end (a baffle): the opening is 2 % of the
// mask, under the 97 % target, yet the only way from one side to the other. The cover
// takes it, so the rectangles stay connected.
TEST(RectangleCover, CoversANeckThatJoinsTwoPiecesPastTheTargetCoverage) {
  const int rows = 50, cols = 101;
  std::vector<uint8_t> mask(static_cast<size_t>(rows) * cols, 1);
  for (int r = 0; r < 45; ++r) mask[static_cast<size_t>(r) * cols + 50] = 0;  // the wall; rows 45-49 open
  RectangleCoverOptions options;
  options.grow_over_covered = false;
  const std::vector<CellRect> cover = GreedyRectangleCover(mask, rows, cols, options);
  bool opening_covered = false;
  for (const CellRect& r : cover) {
    opening_covered |= r.col0 <= 50 && r.col0 + r.cols > 50 && r.row0 + r.rows > 45;
  }
  EXPECT_TRUE(opening_covered);
  options.connect_pieces = false;  // the cover as before: the two halves alone reach 97 %
  for (const CellRect& r : GreedyRectangleCover(mask, rows, cols, options)) {
    EXPECT_FALSE(r.col0 <= 50 && r.col0 + r.cols > 50) << r.row0 << " " << r.col0 << " " << r.rows << " " << r.cols;
  }
}

}  // namespace
}  // namespace mfp
