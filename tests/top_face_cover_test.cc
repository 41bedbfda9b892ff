// Top-face regions where boxes cover one another (TopFaceRegions): every point of every
// region must be a foothold on the true boxes (FootOnTrueSurface: on a top face, inside
// its edge margin, nothing solid above). The generated rough field's two grids overlap
// at the turn, and a region of a lower cell that ran under a higher one put a foot
// inside the higher cell (hexapod_rough_turn_83, step 148).
#include <gtest/gtest.h>

#include "geometry/internal/convex_polygon_difference.h"
#include "geometry/terrain_description.h"
#include "terrain/quality/terrain_quality.h"

namespace mfp {
namespace {

TerrainBox Box(const Eigen::Vector3d& top_centre, const Eigen::Vector3d& size, const Eigen::Vector3d& rpy = {0, 0, 0}) {
  TerrainBox b;
  b.size_m = size;
  b.rpy_rad = rpy;
  b.center_world_m = top_centre - BoxRotation(b) * Eigen::Vector3d(0, 0, size.z() / 2);
  return b;
}

// Points of a region on a grid (and its vertices) that are not footholds on the true boxes.
int PointsOffTheSurface(const TerrainDescription& terrain, const ConvexRegion& region, double margin_m) {
  Eigen::Vector2d lo = region.vertices_world_m[0].head<2>(), hi = lo;
  for (const auto& v : region.vertices_world_m) lo = lo.cwiseMin(v.head<2>()), hi = hi.cwiseMax(v.head<2>());
  std::vector<Eigen::Vector3d> points = region.vertices_world_m;
  const int n = 25;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector2d xy = lo + (hi - lo).cwiseProduct(Eigen::Vector2d(double(i) / n, double(j) / n));
      const Eigen::Vector3d p(xy.x(), xy.y(), region.HeightAt(xy.x(), xy.y()));
      if (RegionContains(region, p, 0.0)) points.push_back(p);
    }
  }
  int off = 0;
  // The course checker's margin: the edge margin less the solver's 1 mm feasibility tolerance.
  for (const auto& p : points) off += FootOnTrueSurface(terrain, p, margin_m - 1e-3, 0.5, 0.025) ? 0 : 1;
  return off;
}

double TotalArea(const std::vector<ConvexRegion>& regions) {
  double a = 0.0;
  for (const auto& r : regions) a += r.area_m2;
  return a;
}

TEST(ConvexPolygonMinus, CutsAGrownSquareOutOfASquare) {
  const std::vector<Eigen::Vector2d> unit = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Eigen::Vector2d> corner = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  double area = 0.0;
  for (const auto& p : ConvexPolygonMinus(unit, corner, 0.0, 0.0)) area += PolygonArea2d(p);
  EXPECT_NEAR(area, 0.75, 1e-12);
  area = 0.0;
  for (const auto& p : ConvexPolygonMinus(unit, corner, 0.1, 0.0)) area += PolygonArea2d(p);
  EXPECT_NEAR(area, 1.0 - 0.6 * 0.6, 1e-12);
  const std::vector<Eigen::Vector2d> far = {{5, 5}, {6, 5}, {6, 6}};
  ASSERT_EQ(ConvexPolygonMinus(unit, far, 0.1, 0.0).size(), 1u);
  EXPECT_TRUE(ConvexPolygonMinus(unit, {{-1, -1}, {2, -1}, {2, 2}, {-1, 2}}, 0.0, 0.0).empty());
}

// Two cells of the rough field's grids: the higher one overlaps a corner of the lower one.
TEST(TopFaceRegions, ALowerCellLosesWhatAHigherOverlappingCellCovers) {
  const double c = 0.092, inset = 0.02;
  TerrainDescription terrain;
  terrain.boxes = {Box({0, 0, 0.015}, {c, c, 0.1}), Box({0.05, 0.05, 0.045}, {c, c, 0.1})};
  const std::vector<ConvexRegion> regions = TopFaceRegions(terrain, inset, 0.5);
  ASSERT_FALSE(regions.empty());
  for (const ConvexRegion& r : regions) EXPECT_EQ(PointsOffTheSurface(terrain, r, inset), 0) << "region " << r.id;
  // The lower face inset: a 0.052 m square; the higher cell's footprint grown by the inset
  // takes a 0.042 m square of it. The higher face is whole.
  const double half = c / 2 - inset;
  EXPECT_NEAR(TotalArea(regions), (2 * half) * (2 * half) - 0.042 * 0.042 + (2 * half) * (2 * half), 1e-9);
  // A foothold left on the lower cell, away from the higher one.
  EXPECT_GE(FindRegionBelow(regions, -0.02, -0.02, 0.0), 0);
  EXPECT_NEAR(regions[FindRegionBelow(regions, -0.02, -0.02, 0.0)].HeightAt(-0.02, -0.02), 0.015, 1e-12);
}

// Abutting boxes, higher or not, only touch a face inset by the margin: it stays whole,
// one region (the beams course: a narrower, higher beam at a platform's edge).
TEST(TopFaceRegions, AFaceAtTheSameHeightOrBelowOrAbuttingDoesNotCut) {
  TerrainDescription terrain;
  terrain.boxes = {Box({0, 0, 0.0}, {0.2, 0.2, 0.1}), Box({0.2, 0, 0.0}, {0.2, 0.2, 0.1}),
                   Box({0, 0.15, -0.03}, {0.2, 0.2, 0.1}), Box({0.4, -0.03, 0.05}, {0.2, 0.1, 0.1})};
  const std::vector<ConvexRegion> regions = TopFaceRegions(terrain, 0.02, 0.5);
  // The two abutting boxes keep whole faces (0.16 m squares); the lower one under the
  // first loses a strip up to 0.02 m beyond the first box (y from 0.07 to 0.12).
  ASSERT_EQ(regions.size(), 4u);
  EXPECT_NEAR(regions[0].area_m2, 0.16 * 0.16, 1e-9);
  EXPECT_NEAR(regions[1].area_m2, 0.16 * 0.16, 1e-9);
  EXPECT_NEAR(regions[2].area_m2, 0.16 * (0.23 - 0.12), 1e-9);
}

TEST(TopFaceRegions, ABoxOnASlabAndARampDippingIntoItLeaveOnlyFootholds) {
  TerrainDescription terrain;
  terrain.boxes = {Box({0, 0, 0}, {2.0, 1.0, 0.1}),                // slab, top z = 0
                   Box({-0.5, 0, 0.1}, {0.3, 0.3, 0.1}),           // a block standing on it
                   Box({0.5, 0, 0.0}, {0.6, 0.4, 0.1}, {0, -0.2, 0})};  // a ramp half under the slab's top
  const double inset = 0.03;
  const std::vector<ConvexRegion> regions = TopFaceRegions(terrain, inset, 0.5);
  for (const ConvexRegion& r : regions) EXPECT_EQ(PointsOffTheSurface(terrain, r, inset), 0) << "region " << r.id;
  // The block's top and the ramp's upper half are footholds, and so is the slab beside them.
  const int on_block = FindRegionBelow(regions, -0.5, 0.0, 0.0);
  ASSERT_GE(on_block, 0);
  EXPECT_NEAR(regions[on_block].HeightAt(-0.5, 0.0), 0.1, 1e-9);
  const int on_ramp = FindRegionBelow(regions, 0.7, 0.0, 0.0);
  ASSERT_GE(on_ramp, 0);
  EXPECT_GT(regions[on_ramp].HeightAt(0.7, 0.0), 0.0);
  EXPECT_GE(FindRegionBelow(regions, 0.0, 0.4, 0.0), 0);
}

}  // namespace
}  // namespace mfp
