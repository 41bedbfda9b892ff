// Convex regions from polygons, box top faces, containment and lookup.
#include "geometry/convex_region.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "base/check.h"
#include "geometry/convex_polygon_distance.h"
#include "geometry/terrain_description.h"

namespace mfp {
namespace {

TEST(ConvexRegion, UnitSquareRows) {
  // Clockwise input is reordered counter-clockwise; rows are the four edges (outward unit
  // normals, b = distance of the edge from the origin) and the plane z = 0 twice.
  const ConvexRegion r = MakeRegionFromPolygon(3, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, 0.01);
  EXPECT_EQ(r.id, 3);
  ASSERT_EQ(r.A.rows(), 6);
  EXPECT_NEAR(r.area_m2, 1.0, 1e-12);
  EXPECT_NEAR(r.SlopeRad(), 0.0, 1e-12);
  EXPECT_TRUE(RegionContains(r, {0.5, 0.5, 0.0}, 0.0));
  EXPECT_TRUE(RegionContains(r, {0.5, 0.5, 0.01}, 1e-12));   // within the plane slab
  EXPECT_FALSE(RegionContains(r, {0.5, 0.5, 0.02}, 1e-12));  // above it
  EXPECT_NEAR(RegionViolation(r, {1.2, 0.5, 0.0}), 0.2, 1e-12);
  EXPECT_NEAR(RegionViolation(r, {0.5, 0.5, 0.0}), -0.01, 1e-12);  // the plane rows bind first
  // Every edge row is a unit outward normal with a vertex on it.
  for (int row = 0; row < 4; ++row) {
    EXPECT_NEAR(r.A.row(row).norm(), 1.0, 1e-12);
    EXPECT_NEAR(r.A(row, 2), 0.0, 1e-12);
  }
}

TEST(ConvexRegion, TiltedPlane) {
  // The plane z = 0.1 x, pitched by atan(0.1): heights follow it and the normal tilts back.
  const ConvexRegion r = MakeRegionFromPolygon(0, {{0, 0, 0}, {1, 0, 0.1}, {1, 1, 0.1}, {0, 1, 0}}, 0.0);
  EXPECT_NEAR(r.HeightAt(0.5, 0.5), 0.05, 1e-12);
  EXPECT_NEAR(r.SlopeRad(), std::atan(0.1), 1e-12);
  EXPECT_TRUE(RegionContains(r, {0.5, 0.2, 0.05}, 1e-9));
  EXPECT_FALSE(RegionContains(r, {0.5, 0.2, 0.06}, 1e-6));
  EXPECT_NEAR(r.area_m2, std::sqrt(1.0 + 0.01), 1e-12);
}

TEST(ConvexRegion, RejectsBadPolygons) {
  EXPECT_THROW(MakeRegionFromPolygon(0, {{0, 0, 0}, {1, 0, 0}}, 0.0), InputError);
  EXPECT_THROW(MakeRegionFromPolygon(0, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 0.0), InputError);  // collinear
  // An L-shaped (non-convex) outline.
  EXPECT_THROW(MakeRegionFromPolygon(0, {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, 0.0),
               InputError);
  // Not coplanar: one corner 5 cm up with a 1 cm tolerance.
  EXPECT_THROW(MakeRegionFromPolygon(0, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.05}, {0, 1, 0}}, 0.01), InputError);
  EXPECT_THROW(MakeRegionFromPolygon(0, {{0, 0, 0}, {1, 0, std::nan("")}, {1, 1, 0}}, 0.0), InputError);
}

TEST(ConvexRegion, FindRegionBelowPicksTheHighestSurface) {
  const std::vector<ConvexRegion> regions = {
      MakeRegionFromPolygon(0, {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, 0.0),
      MakeRegionFromPolygon(1, {{0.5, 0.5, 0.2}, {1, 0.5, 0.2}, {1, 1, 0.2}, {0.5, 1, 0.2}}, 0.0)};
  EXPECT_EQ(FindRegionBelow(regions, 0.75, 0.75, 0.0), 1);
  EXPECT_EQ(FindRegionBelow(regions, 1.5, 1.5, 0.0), 0);
  EXPECT_EQ(FindRegionBelow(regions, 3.0, 1.5, 0.0), -1);
  EXPECT_EQ(FindRegionBelow(regions, 2.05, 1.5, 0.1), 0);  // within the horizontal tolerance
}

TEST(TerrainDescription, TopFacesOfBoxes) {
  TerrainDescription terrain;
  TerrainBox flat;
  flat.center_world_m = {0, 0, -0.05};
  flat.size_m = {1.0, 0.6, 0.1};
  TerrainBox tilted;
  tilted.center_world_m = {2, 0, 0};
  tilted.size_m = {0.5, 0.5, 0.1};
  tilted.rpy_rad = {0.0, 0.2, 0.0};  // pitched 0.2 rad
  TerrainBox steep = tilted;
  steep.center_world_m = {4, 0, 0};  // apart: in the tilted box it would stick out of its face
  steep.rpy_rad = {0.0, 0.8, 0.0};   // steeper than the 0.5 rad limit
  terrain.boxes = {flat, tilted, steep};
  const std::vector<ConvexRegion> regions = TopFaceRegions(terrain, 0.05, 0.5);
  ASSERT_EQ(regions.size(), 2u);
  // The flat top face z = 0, inset by 5 cm on every side: 0.9 x 0.5.
  EXPECT_NEAR(regions[0].area_m2, 0.9 * 0.5, 1e-9);
  EXPECT_NEAR(regions[0].HeightAt(0.3, 0.1), 0.0, 1e-12);
  EXPECT_TRUE(RegionContains(regions[0], {0.44, 0.24, 0.0}, 1e-9));
  EXPECT_FALSE(RegionContains(regions[0], {0.46, 0.0, 0.0}, 1e-9));
  // The pitched box: slope 0.2 rad, centre of the face 0.05 m along the box's up axis.
  EXPECT_NEAR(regions[1].SlopeRad(), 0.2, 1e-9);
  const Eigen::Vector3d up(std::sin(0.2), 0.0, std::cos(0.2));
  const Eigen::Vector3d face_centre = tilted.center_world_m + 0.05 * up;
  EXPECT_TRUE(RegionContains(regions[1], face_centre, 1e-9));
}

TEST(ConvexRegion, PlanDistanceIsZeroInsideAndToTheNearestEdgeOrCornerOutside) {
  // The unit square, given clockwise (MakeRegionFromPolygon turns it counter-clockwise).
  const ConvexRegion r = MakeRegionFromPolygon(0, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, 0.0);
  EXPECT_EQ(PlanDistanceToRegion(r, Eigen::Vector2d(0.5, 0.5)), 0.0);
  EXPECT_EQ(PlanDistanceToRegion(r, Eigen::Vector2d(1.0, 0.3)), 0.0);             // on an edge
  EXPECT_NEAR(PlanDistanceToRegion(r, Eigen::Vector2d(2.0, 0.5)), 1.0, 1e-15);    // beside an edge
  EXPECT_NEAR(PlanDistanceToRegion(r, Eigen::Vector2d(2.0, 2.0)), std::sqrt(2.0), 1e-15);  // past a corner
  EXPECT_NEAR(PlanDistanceToRegion(r, Eigen::Vector2d(0.5, -0.25)), 0.25, 1e-15);
}


TEST(ConvexPolygonDistance, ZeroWhenTheyMeetOtherwiseVertexToSide) {
  const std::array<Eigen::Vector2d, 4> square = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1),
                                                 Eigen::Vector2d(0, 1)};
  auto moved = [&](double dx, double dy) {
    std::vector<Eigen::Vector2d> out;
    for (const Eigen::Vector2d& v : square) out.push_back(v + Eigen::Vector2d(dx, dy));
    return out;
  };
  EXPECT_EQ(ConvexPolygonDistance(square, moved(0.5, 0.5)), 0.0);  // overlapping
  EXPECT_NEAR(ConvexPolygonDistance(square, moved(1.0, 0.3)), 0.0, 1e-15);  // sharing a side
  EXPECT_NEAR(ConvexPolygonDistance(square, moved(1.25, 0.3)), 0.25, 1e-15);  // side to side
  EXPECT_NEAR(ConvexPolygonDistance(moved(1.25, 0.3), square), 0.25, 1e-15);  // either order
  EXPECT_NEAR(ConvexPolygonDistance(square, moved(2.0, 2.0)), std::sqrt(2.0), 1e-15);  // corner to corner
  // A diamond whose corner points at the square's side: vertex to side, not corner to corner.
  const std::vector<Eigen::Vector2d> diamond = {{2.5, 0.5}, {3.5, -0.5}, {4.5, 0.5}, {3.5, 1.5}};
  EXPECT_NEAR(ConvexPolygonDistance(square, diamond), 1.5, 1e-15);
  // A triangle through the square's interior with no vertex inside it: they meet.
  const std::vector<Eigen::Vector2d> crossing = {{-1, 0.4}, {2, 0.4}, {0.5, 3}};
  EXPECT_EQ(ConvexPolygonDistance(square, crossing), 0.0);
  // A repeated vertex (a side without length) separates nothing.
  const std::vector<Eigen::Vector2d> repeated = {{0.2, 0.2}, {0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}};
  EXPECT_EQ(ConvexPolygonDistance(square, repeated), 0.0);
}

// The early answer is the distance's: on random pairs of convex polygons (apart, touching
// or overlapping), at limits just below, at and just above the distance.
TEST(ConvexPolygonDistance, NearerThanALimitAnswersAsTheDistanceDoes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0), angle(0.0, 2 * M_PI), size(0.1, 1.5);
  auto polygon = [&](int n) {  // a regular n-gon, turned and moved
    const double a0 = angle(rng), r = size(rng);
    const Eigen::Vector2d centre(u(rng), u(rng));
    std::vector<Eigen::Vector2d> out;
    for (int k = 0; k < n; ++k) out.push_back(centre + r * Eigen::Vector2d(std::cos(a0 + 2 * M_PI * k / n), std::sin(a0 + 2 * M_PI * k / n)));
    return out;
  };
  int apart = 0, met = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::vector<Eigen::Vector2d> p = polygon(3 + trial % 6), q = polygon(3 + trial / 6 % 4);
    const double d = ConvexPolygonDistance(p, q);
    (d > 0.0 ? apart : met)++;
    for (double limit : {std::nextafter(d, -INFINITY), d, std::nextafter(d, INFINITY), d + 0.1, d - 0.1}) {
      EXPECT_EQ(ConvexPolygonsNearer(p, q, limit), d < limit) << "trial " << trial << ", limit " << limit;
    }
  }
  EXPECT_GT(apart, 100);
  EXPECT_GT(met, 100);
}

}  // namespace
}  // namespace mfp
