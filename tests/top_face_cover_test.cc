// Top-face regions where boxes cover one another (TopFaceRegions): every point of every
// region must be a foothold on the true boxes (FootOnTrueSurface: on a top face, inside
// its edge margin, nothing solid above). The generated rough field's two grids overlap
// at the turn, and a region of a lower cell that ran under a higher one put a foot
// inside the higher cell (hexapod_rough_turn_83, step 148).
#include <gtest/gtest.h>

#include <cmath>

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

// Abutting boxes of one height make one surface, inset once; a higher or lower box
// abutting it only touches the inset face and does not cut it (the beams course: a
// narrower, higher beam at a platform's edge).
TEST(TopFaceRegions, AFaceAtTheSameHeightOrBelowOrAbuttingDoesNotCut) {
  TerrainDescription terrain;
  terrain.boxes = {Box({0, 0, 0.0}, {0.2, 0.2, 0.1}), Box({0.2, 0, 0.0}, {0.2, 0.2, 0.1}),
                   Box({0, 0.15, -0.03}, {0.2, 0.2, 0.1}), Box({0.4, -0.03, 0.05}, {0.2, 0.1, 0.1})};
  const std::vector<ConvexRegion> regions = TopFaceRegions(terrain, 0.02, 0.5);
  // The two abutting boxes make one face, a 0.36 x 0.16 m rectangle (no strip lost along
  // their seam); the lower one under the first loses a strip up to 0.02 m beyond the
  // first box (y from 0.07 to 0.12); the higher beam is whole.
  ASSERT_EQ(regions.size(), 3u);
  EXPECT_NEAR(regions[0].area_m2, 0.36 * 0.16, 1e-9);
  EXPECT_NEAR(regions[1].area_m2, 0.16 * (0.23 - 0.12), 1e-9);
  EXPECT_NEAR(regions[2].area_m2, 0.16 * 0.06, 1e-9);
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

// A half-ring walkway 0.6 m wide made as users make one: n boxes along the arc, each
// rotated to its tangent, long enough that neighbours meet at the outer edge (they
// overlap toward the inner edge), or as long as the arc at mid radius (wedge-shaped gaps
// open toward the outer edge). Top at z = 0.
TerrainDescription HalfRing(int n, double mid_radius_m, double width_m, bool gaps = false) {
  TerrainDescription terrain;
  const double outer = mid_radius_m + width_m / 2;
  const double length = gaps ? mid_radius_m * M_PI / n : 2 * outer * std::tan(M_PI / (2 * n));
  for (int k = 0; k < n; ++k) {
    const double a = (k + 0.5) * M_PI / n;
    terrain.boxes.push_back(Box({mid_radius_m * std::cos(a), mid_radius_m * std::sin(a), 0.0}, {length, width_m, 0.1},
                                {0, 0, a + M_PI / 2}));
  }
  return terrain;
}

struct Coverage {
  long surface = 0;  // grid points whose foot disk lies on the true surface
  long covered = 0;  // of them, inside a region
  double Fraction() const { return surface > 0 ? double(covered) / surface : 0.0; }
};

// Area sampling on a 2 cm grid over [lo, hi]: the true surface inset by margin_m
// (FootOnTrueSurface: the margin disk on real top surface) against the regions.
Coverage CoverageOf(const TerrainDescription& terrain, const std::vector<ConvexRegion>& regions, double margin_m,
                    const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double z_m) {
  Coverage c;
  for (double x = lo.x(); x <= hi.x(); x += 0.02) {
    for (double y = lo.y(); y <= hi.y(); y += 0.02) {
      if (!FootOnTrueSurface(terrain, {x, y, z_m}, margin_m, 0.5, 1e-3)) continue;
      ++c.surface;
      const int r = FindRegionBelow(regions, x, y, 0.0);
      if (r >= 0 && std::abs(regions[r].HeightAt(x, y) - z_m) < 1e-6) ++c.covered;
    }
  }
  return c;
}

// Regions made of each box's face inset by itself, less the boxes standing higher: what
// TopFaceRegions gave before coplanar faces were joined.
std::vector<ConvexRegion> EachFaceAlone(const TerrainDescription& terrain, double inset_m) {
  std::vector<ConvexRegion> regions;
  for (const TerrainBox& box : terrain.boxes) {
    const double top = (box.center_world_m + BoxRotation(box).col(2) * box.size_m.z() / 2).z();
    TerrainDescription one;
    one.boxes = {box};
    for (const TerrainBox& other : terrain.boxes) {
      if ((other.center_world_m + BoxRotation(other).col(2) * other.size_m.z() / 2).z() > top + 0.01) one.boxes.push_back(other);
    }
    for (ConvexRegion& r : TopFaceRegions(one, inset_m, 0.5)) {
      const Eigen::Vector3d& v = r.vertices_world_m[0];
      if (std::abs(v.z() - top) < 1e-9) regions.push_back(std::move(r));
    }
  }
  return regions;
}

// Issue 29: the ring's regions covered 83 % of its surface; the boxes' faces inset one
// by one leave a strip twice the inset wide across the walkway at every seam.
TEST(TopFaceRegions, ARingWalkwayIsCoveredAsOneSurface) {
  const double inset = 0.03;  // foot radius + edge margin
  for (int n : {12, 24, -16}) {  // negative: |n| boxes with gaps at the outer edge
    const TerrainDescription ring = HalfRing(std::abs(n), 1.2, 0.6, n < 0);
    const std::vector<ConvexRegion> regions = TopFaceRegions(ring, inset, 0.5);
    const Coverage joined = CoverageOf(ring, regions, inset, {-1.6, -0.1}, {1.6, 1.6}, 0.0);
    const Coverage alone = CoverageOf(ring, EachFaceAlone(ring, inset), inset, {-1.6, -0.1}, {1.6, 1.6}, 0.0);
    std::printf("ring of %d boxes: %zu regions cover %.1f %% of %ld surface points (faces inset alone: %.1f %%)\n", n,
                regions.size(), 100 * joined.Fraction(), joined.surface, 100 * alone.Fraction());
    EXPECT_GE(joined.Fraction(), 0.95) << n << " boxes";
    // Few regions: about one a box where the boxes meet, a few more beside gaps.
    EXPECT_LE(regions.size(), size_t((n < 0 ? 3 : 2) * std::abs(n))) << n << " boxes";
    for (const ConvexRegion& r : regions) EXPECT_EQ(PointsOffTheSurface(ring, r, inset), 0) << "region " << r.id;
  }
}

// A floor of four tiles with a spiral stair's landing, rotated 30 degrees, standing on it
// across the tiles' seams: a start stance 10 cm inside the real floor, straddling the
// seams, is on regions; no region point is off the floor or within the inset of the landing.
TEST(TopFaceRegions, TheFloorBesideARotatedLandingHasNoHolesAtTheTilesSeams) {
  TerrainDescription terrain;
  for (double x : {-1.0, 1.0}) {
    for (double y : {-1.0, 1.0}) terrain.boxes.push_back(Box({x, y, 0.0}, {2.0, 2.0, 0.1}));
  }
  terrain.boxes.push_back(Box({0.6, 0.6, 0.6}, {0.8, 0.8, 0.6}, {0, 0, M_PI / 6}));  // the landing
  const double inset = 0.03;
  const std::vector<ConvexRegion> regions = TopFaceRegions(terrain, inset, 0.5);
  for (const ConvexRegion& r : regions) EXPECT_EQ(PointsOffTheSurface(terrain, r, inset), 0) << "region " << r.id;
  // A stance straddling the seams, 10 cm from the landing's side.
  const std::vector<Eigen::Vector2d> feet = {{0.0, -0.2}, {-0.3, 0.0}, {0.0, 0.05}, {-0.1, 0.3}};
  for (const Eigen::Vector2d& f : feet) {
    EXPECT_TRUE(FootOnTrueSurface(terrain, {f.x(), f.y(), 0.0}, 0.1, 0.5, 1e-3)) << f.transpose();
    const int r = FindRegionBelow(regions, f.x(), f.y(), 0.0);
    ASSERT_GE(r, 0) << f.transpose();
    EXPECT_NEAR(regions[r].HeightAt(f.x(), f.y()), 0.0, 1e-9);
  }
  const Coverage floor = CoverageOf(terrain, regions, inset, {-2, -2}, {2, 2}, 0.0);
  const Coverage alone = CoverageOf(terrain, EachFaceAlone(terrain, inset), inset, {-2, -2}, {2, 2}, 0.0);
  std::printf("tiled floor beside a rotated landing: %zu regions cover %.1f %% (faces inset alone: %.1f %%)\n",
              regions.size(), 100 * floor.Fraction(), 100 * alone.Fraction());
  EXPECT_GE(floor.Fraction(), 0.97);
  EXPECT_LE(regions.size(), 12u);
}

}  // namespace
}  // namespace mfp
