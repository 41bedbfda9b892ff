// Which regions a plan and one window can use (geometry/region_reachability.h).
#include "geometry/region_reachability.h"

#include <gtest/gtest.h>

namespace mfp {
namespace {

ConvexRegion Square(int id, double x, double y, double z, double half) {
  return MakeRegionFromPolygon(
      id, {{x - half, y - half, z}, {x + half, y - half, z}, {x + half, y + half, z}, {x - half, y + half, z}}, 0.0);
}

TEST(RegionReachabilityTest, CeilingAndFarStonesAreUnreachableStepsAreNot) {
  const std::vector<ConvexRegion> regions = {
      Square(0, 0.0, 0.0, 0.0, 0.5),   // floor under the start
      Square(1, 0.0, 0.0, 2.8, 0.5),   // ceiling straight above it
      Square(2, 0.7, 0.0, 0.05, 0.1),  // a stone one step away, 5 cm up
      Square(3, 0.95, 0.0, 0.1, 0.1),  // the next, reached through the first
      Square(4, 1.2, 0.0, 0.4, 0.1),   // 30 cm up from there: more than dz_max
      Square(5, 3.0, 0.0, 0.0, 0.1),   // 2 m beyond any step
  };
  const std::vector<Eigen::Vector3d> feet = {{-0.1, 0.1, 0.0}, {0.1, -0.1, 0.0}};
  EXPECT_EQ(ReachableRegionIndices(regions, feet, 0.2, 0.08, 0.01), (std::vector<int>{0, 2, 3}));
  // With the start foot on no region, nothing is reachable.
  EXPECT_TRUE(ReachableRegionIndices(regions, {{5.0, 5.0, 0.0}}, 0.2, 0.08, 0.01)->empty());
  // One step per leg reaches the first stone only; two reach the second as well.
  EXPECT_EQ(WindowRegionIndices(regions, feet, 1, 0.55, 0.08), (std::vector<int>{0, 2}));
  EXPECT_EQ(WindowRegionIndices(regions, feet, 2, 0.55, 0.08), (std::vector<int>{0, 2, 3}));
}

TEST(RegionReachabilityTest, PlanarDistanceOfCrossingRectanglesIsZero) {
  const ConvexRegion a = MakeRegionFromPolygon(0, {{-1, -0.1, 0}, {1, -0.1, 0}, {1, 0.1, 0}, {-1, 0.1, 0}}, 0.0);
  const ConvexRegion b = MakeRegionFromPolygon(1, {{-0.1, -1, 0}, {0.1, -1, 0}, {0.1, 1, 0}, {-0.1, 1, 0}}, 0.0);
  EXPECT_EQ(RegionPlanarDistance(a, b), 0.0);
  EXPECT_NEAR(RegionPlanarDistance(Square(0, 0, 0, 0, 0.1), Square(1, 0.5, 0, 0, 0.1)), 0.3, 1e-12);
}

}  // namespace
}  // namespace mfp
