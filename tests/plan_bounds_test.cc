// The plan-view bounding box of a region (geometry/plan_bounds.h).
#include "geometry/plan_bounds.h"

#include <gtest/gtest.h>

#include <vector>

namespace mfp {
namespace {

TEST(PlanBounds, IsTheSmallestBoxOverThePolygonsVerticesInPlanView) {
  // A tilted pentagon: its heights play no part, and no vertex lies on two extremes.
  const ConvexRegion r =
      MakeRegionFromPolygon(4, {{1.0, -0.5, 0.1}, {2.5, 0.0, 0.25}, {2.0, 1.5, 0.2}, {0.5, 1.0, 0.05}, {0.25, 0.25, 0.025}},
                            1e-9);
  const Eigen::AlignedBox2d box = PlanBounds(r);
  ASSERT_FALSE(box.isEmpty());
  EXPECT_EQ(box.min(), Eigen::Vector2d(0.25, -0.5));
  EXPECT_EQ(box.max(), Eigen::Vector2d(2.5, 1.5));
  for (const Eigen::Vector3d& v : r.vertices_world_m) EXPECT_TRUE(box.contains(Eigen::Vector2d(v.head<2>())));
}

TEST(PlanBounds, MeetsABoxItOnlyTouchesAndNotOneJustBeyond) {
  // The closed boxes the planner's nearness tests compare (stance_route.cc, stop_report.cc).
  const ConvexRegion square = MakeRegionFromPolygon(0, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.0);
  const Eigen::AlignedBox2d box = PlanBounds(square);
  EXPECT_TRUE(box.intersects(Eigen::AlignedBox2d(Eigen::Vector2d(1, 1), Eigen::Vector2d(2, 2))));  // a corner
  EXPECT_TRUE(box.intersects(Eigen::AlignedBox2d(Eigen::Vector2d(-1, 0.5), Eigen::Vector2d(0, 0.6))));  // a side
  EXPECT_FALSE(box.intersects(Eigen::AlignedBox2d(Eigen::Vector2d(1 + 1e-9, 0), Eigen::Vector2d(2, 1))));
  EXPECT_FALSE(box.intersects(Eigen::AlignedBox2d(Eigen::Vector2d(0, -2), Eigen::Vector2d(1, -1e-9))));
}

TEST(PlanBounds, OfARegionWithoutVerticesIsEmptyAndMeetsNothing) {
  const ConvexRegion none;
  const Eigen::AlignedBox2d box = PlanBounds(none);
  EXPECT_TRUE(box.isEmpty());
  EXPECT_FALSE(box.intersects(Eigen::AlignedBox2d(Eigen::Vector2d(-1e300, -1e300), Eigen::Vector2d(1e300, 1e300))));
}

}  // namespace
}  // namespace mfp
