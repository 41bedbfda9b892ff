// The voxel judge's certifiable floor (issue 25): the seen floor eroded as a set of cell
// squares, and the older centre-to-centre figure beside it.
#include <gtest/gtest.h>

#include <vector>

#include "geometry/convex_region.h"
#include "terrain/extraction/occupancy_map.h"
#include "terrain/quality/voxel_quality.h"

namespace mfp {
namespace {

constexpr double kRes = 0.05;

// A 20 x 20 floor of one-voxel columns, seen from above, with no column at (10, 10).
OccupancyMap FloorWithAHole() {
  OccupancyMap map;
  map.resolution_m = kRes;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      const double x = (i + 0.5) * kRes, y = (j + 0.5) * kRes;
      if (!(i == 10 && j == 10)) map.leaves.push_back({{x, y, 0.5 * kRes}, kRes});
      for (int k = 1; k <= 12; ++k) map.free_leaves.push_back({{x, y, (k + 0.5) * kRes}, kRes});
    }
  }
  return map;
}

TEST(VoxelQuality, TheCertifiableFloorIsTheFloorErodedAsASetOfCellSquares) {
  VoxelQualityOptions options;
  options.clearance_m = 0.4;
  options.erosion_m = 0.09;  // 1.8 cells: a 3 cm foot, 1 cm and a voxel
  const VoxelQuality q = JudgeRegionsAgainstVoxels({}, FloorWithAHole(), options);
  EXPECT_EQ(q.seen_floor_cells, 399);
  // As a set: a centre is kept when no square outside the floor comes within 1.8 cells,
  // i.e. the 5 x 5 cells around it but the corners are floor. 16 x 16 centres clear the
  // map's border; 21 of them are that close to the hole.
  EXPECT_EQ(q.certifiable_floor_cells, 16 * 16 - 21);
  // Centre to centre: only the 3 x 3 cells around it: 18 x 18 clear the border, 9 the hole.
  EXPECT_EQ(q.certifiable_centre_floor_cells, 18 * 18 - 9);
  EXPECT_EQ(q.certifiable_covered_cells, 0);
}

}  // namespace
}  // namespace mfp
