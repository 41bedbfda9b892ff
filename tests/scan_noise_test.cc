// Sensor noise versus real edges (issue 25): small groups of one-voxel pits and bumps stay
// in a floor's region, a region's height is its own surface's, a one-voxel trench is a
// drop that no region spans, an unseen cell is floor only where nothing lower (or above)
// was seen and no ray passed where the floor would be.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/convex_region.h"
#include "terrain/extraction/occupancy_map.h"
#include "terrain/extraction/region_extractor.h"

namespace mfp {
namespace {

constexpr double kRes = 0.02;
constexpr int kMissing = -99;  // no occupied voxel in the column

// A floor of n x n columns, two voxels thick with its top voxel at k = 0 (top at z = kRes),
// each column's top moved by offset(i, j) voxels (kMissing: nothing in the column).
// ground_below: a voxel at k = -10 under every column (a lower surface seen). seen: free
// voxels from k = 1 up (known free above the floor), and at k = 0 where erased(i, j)
// (also at k = -1 with ray_under).
struct FloorSpec {
  int n = 40;
  std::function<int(int, int)> offset = [](int, int) { return 0; };
  bool ground_below = false;
  bool seen = false;
  std::function<bool(int, int)> erased = [](int, int) { return false; };
  bool ray_under = false;
};

OccupancyMap Floor(const FloorSpec& spec) {
  OccupancyMap map;
  map.resolution_m = kRes;
  for (int i = 0; i < spec.n; ++i) {
    for (int j = 0; j < spec.n; ++j) {
      const double x = (i + 0.5) * kRes, y = (j + 0.5) * kRes;
      if (spec.ground_below) map.leaves.push_back({{x, y, -9.5 * kRes}, kRes});
      const int d = spec.offset(i, j);
      if (d != kMissing) {
        for (int k = std::min(0, d) - 1; k <= d; ++k) map.leaves.push_back({{x, y, (k + 0.5) * kRes}, kRes});
      }
      if (!spec.seen) continue;
      const bool erased = d == kMissing && spec.erased(i, j);
      const int free_from = erased ? (spec.ray_under ? -1 : 0) : std::max(1, d + 1);
      for (int k = free_from; k < 40; ++k) map.free_leaves.push_back({{x, y, (k + 0.5) * kRes}, kRes});
    }
  }
  return map;
}

RegionExtractorOptions TestOptions() {
  RegionExtractorOptions options;
  options.foot_radius_m = 0.03;
  options.clearance_m = 0.4;
  return options;
}

RegionExtractionResult Extract(const OccupancyMap& map,
                               int noise_max_cells = RegionExtractorOptions().noise_max_cells) {
  RegionExtractorOptions options = TestOptions();
  options.noise_max_cells = noise_max_cells;
  return ExtractRegions(map, options);
}

// The plan area of the floor [0, side]^2 that the regions cover, each point once however
// many regions hold it (sampled every 2 mm) [m^2].
double CoveredArea(const RegionExtractionResult& r, double side_m) {
  constexpr double kStep = 0.002;
  const int n = static_cast<int>(std::lround(side_m / kStep));
  std::vector<Eigen::Vector2d> lo, hi;
  for (const ConvexRegion& region : r.regions) {
    Eigen::Vector2d a = region.vertices_world_m.front().head<2>(), b = a;
    for (const Eigen::Vector3d& v : region.vertices_world_m) a = a.cwiseMin(v.head<2>()), b = b.cwiseMax(v.head<2>());
    lo.push_back(a);
    hi.push_back(b);
  }
  int covered = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector2d p((i + 0.5) * kStep, (j + 0.5) * kStep);
      for (size_t k = 0; k < r.regions.size(); ++k) {
        if ((p.array() < lo[k].array()).any() || (p.array() > hi[k].array()).any()) continue;
        if (PlanDistanceToRegion(r.regions[k], p) <= 0.0) {
          ++covered;
          break;
        }
      }
    }
  }
  return covered * kStep * kStep;
}

// What a sound extractor could certify on the n x n floor whose top voxel is moved by
// offset(i, j) (issue 25: the seen floor eroded by the foot, the edge margin and the edge
// uncertainty), when only groups of at most noise_max_cells 4-connected cells one voxel
// off the floor, the same way, are noise; a larger group is an edge: foot centres whose
// disk of that inset stays on the floor and clear of larger groups' cells (sampled every
// 2 mm) [m^2].
double CertifiableArea(int n, const std::function<int(int, int)>& offset, const RegionExtractorOptions& options) {
  std::vector<int> group(static_cast<size_t>(n) * n, -1), size;
  for (int start = 0; start < n * n; ++start) {
    const int level = offset(start / n, start % n);
    if (level == 0 || group[start] >= 0) continue;
    std::vector<int> stack = {start};
    group[start] = static_cast<int>(size.size());
    size.push_back(0);
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      ++size.back();
      const int i = k / n, j = k % n;
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int ii = i + di, jj = j + dj;
        if (ii < 0 || jj < 0 || ii >= n || jj >= n || group[ii * n + jj] >= 0 || offset(ii, jj) != level) continue;
        group[ii * n + jj] = group[start];
        stack.push_back(ii * n + jj);
      }
    }
  }
  auto edge = [&](int i, int j) { return group[i * n + j] >= 0 && size[group[i * n + j]] > options.noise_max_cells; };
  const double inset_m = options.foot_radius_m + options.edge_margin_m + options.edge_uncertainty_voxels * kRes;
  const int reach = static_cast<int>(std::ceil(inset_m / kRes)) + 1;
  constexpr double kStep = 0.002;
  const int samples = static_cast<int>(std::lround(n * kRes / kStep));
  int certifiable = 0;
  for (int a = 0; a < samples; ++a) {
    for (int b = 0; b < samples; ++b) {
      const Eigen::Vector2d p((a + 0.5) * kStep, (b + 0.5) * kStep);
      bool ok = p.minCoeff() >= inset_m && p.maxCoeff() <= n * kRes - inset_m;
      const int pi = static_cast<int>(p.x() / kRes), pj = static_cast<int>(p.y() / kRes);
      for (int i = std::max(0, pi - reach); ok && i <= std::min(n - 1, pi + reach); ++i) {
        for (int j = std::max(0, pj - reach); ok && j <= std::min(n - 1, pj + reach); ++j) {
          const double dx = std::max({0.0, i * kRes - p.x(), p.x() - (i + 1) * kRes});
          const double dy = std::max({0.0, j * kRes - p.y(), p.y() - (j + 1) * kRes});
          ok = !(edge(i, j) && std::hypot(dx, dy) < inset_m);
        }
      }
      certifiable += ok;
    }
  }
  return certifiable * kStep * kStep;
}

double TotalArea(const RegionExtractionResult& r) {
  double a = 0.0;
  for (const ConvexRegion& region : r.regions) a += region.area_m2;
  return a;
}

// Whether some region at the floor's height (within a voxel) holds the plan point xy.
bool FloorRegionHolds(const RegionExtractionResult& r, const Eigen::Vector2d& xy) {
  for (const ConvexRegion& region : r.regions) {
    const bool at_floor = std::abs(region.HeightAt(xy.x(), xy.y()) - kRes) <= kRes;
    if (at_floor && PlanDistanceToRegion(region, xy) <= 0.0) return true;
  }
  return false;
}

Eigen::Vector2d CellCentre(int i, int j) { return {(i + 0.5) * kRes, (j + 0.5) * kRes}; }

// Groups of two by two pits and of three bumps in a row, one voxel off a 1.2 m floor:
// too large for the height map's single-cell repair, small enough to be noise.
int PitsAndBumps(int i, int j) {
  if (i % 12 >= 4 && i % 12 < 6 && j % 10 >= 4 && j % 10 < 6) return -1;
  if (i % 12 == 9 && j % 10 >= 7 && j % 10 < 10) return 1;
  return 0;
}

TEST(ScanNoise, GroupsOfOneVoxelPitsAndBumpsStayInTheFloorsRegion) {
  FloorSpec clean;
  clean.n = 60;
  FloorSpec noisy = clean;
  noisy.offset = PitsAndBumps;
  const RegionExtractionResult a = Extract(Floor(clean)), b = Extract(Floor(noisy)), cut = Extract(Floor(noisy), 0);
  ASSERT_FALSE(a.regions.empty());
  ASSERT_FALSE(b.regions.empty());
  EXPECT_GE(TotalArea(b), 0.95 * TotalArea(a));
  // Cutting the noise out (noise_max_cells 0) shatters the floor: the test tells them apart.
  EXPECT_LT(TotalArea(cut), 0.8 * TotalArea(a));
  // The regions' height is the floor's, not lifted by the bumps nor lowered by the pits.
  for (const ConvexRegion& r : b.regions) EXPECT_NEAR(r.HeightAt(0.6, 0.6), kRes, 0.1 * kRes);
}

// Scattered one-voxel pits and bumps, a tenth of the cells each way, placed by a hash:
// the floor's top voxel jumps as on a real scan, in groups of every size and shape.
int ScatteredNoise(int i, int j) {
  const unsigned h = (static_cast<unsigned>(i) * 73856093u) ^ (static_cast<unsigned>(j) * 19349663u);
  const unsigned bucket = (h ^ (h >> 13)) * 2654435761u >> 24;  // 0..255
  return bucket < 26 ? -1 : bucket < 52 ? 1 : 0;
}

TEST(ScanNoise, AFloorWithScatteredOneVoxelPitsAndBumpsIsOneSurface) {
  FloorSpec clean;
  clean.n = 60;
  FloorSpec noisy = clean;
  noisy.offset = ScatteredNoise;
  const RegionExtractionResult a = Extract(Floor(clean)), b = Extract(Floor(noisy));
  ASSERT_FALSE(a.regions.empty());
  ASSERT_FALSE(b.regions.empty());
  // The floor the regions cover (overlaps once) against what a sound extractor could
  // certify there: the 85 % of the flat floor.
  const double certifiable = CertifiableArea(noisy.n, noisy.offset, TestOptions());
  std::printf("ScanNoise floor: certifiable %.4f m^2, covered clean %.4f, noisy %.4f (%zu regions)\n", certifiable,
              CoveredArea(a, clean.n * kRes), CoveredArea(b, clean.n * kRes), b.regions.size());
  EXPECT_NEAR(CoveredArea(a, clean.n * kRes), CertifiableArea(clean.n, clean.offset, TestOptions()), 0.01);
  EXPECT_GE(CoveredArea(b, clean.n * kRes), 0.85 * certifiable);
  // Every region is the floor's, at its height (the noise averages out), none a level of it.
  for (const ConvexRegion& r : b.regions) EXPECT_NEAR(r.HeightAt(0.6, 0.6), kRes, 0.25 * kRes);
  // Cutting the noise out (noise_max_cells 0) shatters the floor: the test tells them apart.
  EXPECT_LT(CoveredArea(Extract(Floor(noisy), 0), clean.n * kRes), 0.5 * certifiable);
}

TEST(ScanNoise, AStoneOneVoxelAboveTheFloorIsARegionOfItsOwn) {
  FloorSpec spec;
  spec.n = 60;
  // A 0.2 m square stone, room for a foot on it, one voxel up in a floor with scattered noise.
  spec.offset = [](int i, int j) { return i >= 25 && i < 35 && j >= 25 && j < 35 ? 1 : ScatteredNoise(i, j); };
  const RegionExtractionResult r = Extract(Floor(spec));
  bool stone = false;
  for (const ConvexRegion& region : r.regions) {
    if (PlanDistanceToRegion(region, CellCentre(30, 30)) > 0.0) continue;
    EXPECT_NEAR(region.HeightAt(0.6, 0.6), 2 * kRes, 0.05 * kRes) << "a region at the stone is not the stone's";
    stone = true;
  }
  EXPECT_TRUE(stone);
}

TEST(ScanNoise, ARegionBesideAHigherStoneKeepsItsOwnHeight) {
  FloorSpec spec;
  spec.n = 60;
  // A 0.4 m x 0.6 m stone one voxel higher in the floor: its cells join the floor's
  // growth (within a voxel) but are a step, not noise, and must not lift or tilt the
  // floor's plane (fitted to all grown cells, it sat a sixth of a voxel high).
  spec.offset = [](int i, int j) { return i >= 20 && i < 40 && j >= 15 && j < 45 ? 1 : 0; };
  const RegionExtractionResult r = Extract(Floor(spec));
  int floor_regions = 0;
  for (const ConvexRegion& region : r.regions) {
    if (PlanDistanceToRegion(region, CellCentre(5, 5)) <= 0.0) {
      ++floor_regions;
      EXPECT_NEAR(region.HeightAt(0.11, 0.11), kRes, 0.05 * kRes);
    }
    // No floor region reaches onto the stone (its cells, left out of the floor's patch,
    // seed no patch of their own: a region there would be the stone's, at its height).
    if (PlanDistanceToRegion(region, CellCentre(30, 30)) <= 0.0) {
      EXPECT_NEAR(region.HeightAt(0.61, 0.61), 2 * kRes, 0.05 * kRes);
    }
  }
  EXPECT_GE(floor_regions, 1);
}

TEST(ScanNoise, SteppingStonesAcrossAOneVoxelTrenchAreTwoRegionsAndNoneSpansTheDrop) {
  FloorSpec spec;
  spec.n = 61;  // the trench is column i = 30, its bottom 0.5 m down (seen there)
  spec.offset = [](int i, int) { return i == 30 ? -25 : 0; };
  for (bool ground : {false, true}) {
    spec.ground_below = ground;
    const RegionExtractionResult r = Extract(Floor(spec));
    int left = 0, right = 0;
    for (const ConvexRegion& region : r.regions) {
      if (std::abs(region.HeightAt(0.61, 0.6) - kRes) > kRes) continue;  // the trench bottom, not a stone
      double lo = INFINITY, hi = -INFINITY;
      for (const Eigen::Vector3d& v : region.vertices_world_m) lo = std::min(lo, v.x()), hi = std::max(hi, v.x());
      EXPECT_TRUE(hi <= 0.60 + 1e-9 || lo >= 0.62 - 1e-9) << "a region spans the trench: x " << lo << " .. " << hi;
      left += hi <= 0.60 + 1e-9;
      right += lo >= 0.62 - 1e-9;
    }
    EXPECT_GE(left, 1);
    EXPECT_GE(right, 1);
  }
}

TEST(ScanNoise, AShortOneVoxelPitWithItsBottomSeenIsADropNeverBridged) {
  FloorSpec spec;
  // Three cells in a row whose surface was seen 0.2 m down: narrower than the noise
  // limit, yet a drop.
  spec.offset = [](int i, int j) { return i == 20 && j >= 19 && j <= 21 ? -10 : 0; };
  const RegionExtractionResult r = Extract(Floor(spec));
  ASSERT_FALSE(r.regions.empty());
  for (int j = 19; j <= 21; ++j) EXPECT_FALSE(FloorRegionHolds(r, CellCentre(20, j))) << j;
}

TEST(ScanNoise, UnseenCellsAreFloorOnlyWhereNothingLowerWasSeenAndNoRayPassed) {
  const auto hole = [](int i, int j) { return i >= 20 && i <= 21 && j == 20 ? kMissing : 0; };
  FloorSpec spec;
  spec.offset = hole;
  spec.seen = true;
  // Nothing in the two columns and no ray through the floor's level: unseen floor.
  const RegionExtractionResult filled = Extract(Floor(spec));
  EXPECT_TRUE(FloorRegionHolds(filled, CellCentre(20, 20)));
  EXPECT_TRUE(FloorRegionHolds(filled, CellCentre(21, 20)));
  // Ground seen 0.2 m below them: a drop.
  spec.ground_below = true;
  const RegionExtractionResult drop = Extract(Floor(spec));
  EXPECT_FALSE(FloorRegionHolds(drop, CellCentre(20, 20)));
  // A ray passed where the floor would be (known free at its level): erased, not floor.
  spec.ground_below = false;
  spec.erased = [](int, int) { return true; };
  const RegionExtractionResult erased = Extract(Floor(spec));
  EXPECT_FALSE(FloorRegionHolds(erased, CellCentre(20, 20)));
  EXPECT_FALSE(FloorRegionHolds(erased, CellCentre(21, 20)));
}

TEST(ScanNoise, ASingleErasedCellKeepsFeetOffItButAddsNoEdgeUnlessARayWentUnderTheFloor) {
  FloorSpec spec;
  spec.offset = [](int i, int j) { return i == 20 && j == 20 ? kMissing : 0; };
  spec.seen = true;
  spec.erased = [](int, int) { return true; };
  // A ray passed through the floor-level voxel only, floor seen all round: grazing rays
  // erase floor so (docs/unseen_floor.md), and the floor stays one patch, but no foot may
  // stand on the cell the sensor did not see: the regions keep the foot and the margin
  // (4 cm) off it, and no edge uncertainty (2 cm more): 5 cm from the cell is held.
  const RegionExtractionResult erased = Extract(Floor(spec));
  EXPECT_FALSE(FloorRegionHolds(erased, CellCentre(20, 20)));
  EXPECT_TRUE(FloorRegionHolds(erased, CellCentre(23, 20)));
  // A ray also went through the voxel under the floor's level: a hole, an edge.
  spec.ray_under = true;
  EXPECT_FALSE(FloorRegionHolds(Extract(Floor(spec)), CellCentre(23, 20)));
}

}  // namespace
}  // namespace mfp
