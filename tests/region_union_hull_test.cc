// The convex hull of a set of regions seen from above (planner/formulation/internal/region_union_hull.h).
#include "planner/formulation/internal/region_union_hull.h"

#include <gtest/gtest.h>

namespace mfp {
namespace {

ConvexRegion Square(int id, double x0, double x1, double y0, double y1, double z, double tolerance) {
  return MakeRegionFromPolygon(id, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, tolerance);
}

bool Inside(const RegionUnionHull& h, double x, double y) {
  return ((h.A * Eigen::Vector2d(x, y)).array() <= h.b.array() + 1e-12).all();
}

TEST(RegionUnionHull, TwoStonesAndTheGapBetweenThem) {
  // [0, 1] x [0, 1] at z = 0 and [2, 3] x [0.5, 1.5] at z = 0.1 (slabs 0.01 thick): the
  // hull is the hexagon (0,0) (1,0) (3,0.5) (3,1.5) (2,1.5) (0,1).
  const ConvexRegion a = Square(0, 0, 1, 0, 1, 0.0, 0.01), b = Square(1, 2, 3, 0.5, 1.5, 0.1, 0.01);
  const RegionUnionHull h = HullOfRegions({&a, &b});
  EXPECT_EQ(h.A.rows(), 6);
  for (int k = 0; k < h.A.rows(); ++k) EXPECT_NEAR(h.A.row(k).norm(), 1.0, 1e-12);
  for (const ConvexRegion* r : {&a, &b}) {
    for (const Eigen::Vector3d& v : r->vertices_world_m) EXPECT_TRUE(Inside(h, v.x(), v.y())) << v.transpose();
  }
  EXPECT_TRUE(Inside(h, 1.5, 0.5));     // the gap between the stones
  EXPECT_TRUE(Inside(h, 1.5, 1.37));    // just below the edge from (0, 1) to (2, 1.5) (y 1.375 there)
  EXPECT_FALSE(Inside(h, 1.5, 1.38));   // just above it
  EXPECT_FALSE(Inside(h, 1.5, 0.12));   // below the edge from (1, 0) to (3, 0.5) (y 0.125 there)
  EXPECT_FALSE(Inside(h, -0.01, 0.5));
  EXPECT_FALSE(Inside(h, 3.01, 1.0));
  EXPECT_NEAR(h.z_lower_m, -0.01, 1e-12);
  EXPECT_NEAR(h.z_upper_m, 0.11, 1e-12);
}

TEST(RegionUnionHull, AxisAlignedEdgesHaveExactAxisNormals) {
  // Rounding must not leave 1e-17 components: bound propagation would divide by them.
  const ConvexRegion a = Square(0, 0.1, 0.7, 0.3, 0.9, 0.0, 0.0);
  const RegionUnionHull h = HullOfRegions({&a});
  ASSERT_EQ(h.A.rows(), 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE((h.A(k, 0) == 0.0) != (h.A(k, 1) == 0.0)) << h.A.row(k);
  }
}

TEST(RegionUnionHull, CollinearRegionsGiveABoundedStrip) {
  // Two segments on one line (a degenerate union): four half-planes that hold the
  // segment from (0, 0) to (3, 0) and nothing off it.
  ConvexRegion a, b;
  a.vertices_world_m = {{0, 0, 0}, {1, 0, 0}};
  b.vertices_world_m = {{2, 0, 0}, {3, 0, 0}};
  const RegionUnionHull h = HullOfRegions({&a, &b});
  EXPECT_EQ(h.A.rows(), 4);
  EXPECT_TRUE(Inside(h, 1.5, 0.0));
  EXPECT_FALSE(Inside(h, 1.5, 0.01));
  EXPECT_FALSE(Inside(h, 3.01, 0.0));
  EXPECT_FALSE(Inside(h, -0.01, 0.0));
}

}  // namespace
}  // namespace mfp
