// Region extraction on synthetic terrains with known answers (terrain_catalogue.h).
// The maps are voxelised directly; octomap_io_test covers the same path through files.
#include "terrain/extraction/region_extractor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "base/check.h"
#include "terrain/extraction/cell_fate.h"
#include "terrain/extraction/internal/parallel_work.h"
#include "terrain/extraction/voxelize.h"
#include "terrain/quality/terrain_catalogue.h"
#include "terrain/quality/terrain_quality.h"

namespace mfp {
namespace {

constexpr double kRes = 0.02;
constexpr double kEps = 1e-6;

double Deg(double d) { return d * M_PI / 180.0; }

RegionExtractionResult Extract(const TerrainDescription& t, double foot_radius_m = 0.01) {
  RegionExtractorOptions options;
  options.foot_radius_m = foot_radius_m;
  options.max_slope_rad = 0.45;
  return ExtractRegionsFromTerrain(t, options);
}

Eigen::Vector2d Min(const ConvexRegion& r) {
  Eigen::Vector2d lo(INFINITY, INFINITY);
  for (const auto& v : r.vertices_world_m) lo = lo.cwiseMin(v.head<2>());
  return lo;
}
Eigen::Vector2d Max(const ConvexRegion& r) {
  Eigen::Vector2d hi(-INFINITY, -INFINITY);
  for (const auto& v : r.vertices_world_m) hi = hi.cwiseMax(v.head<2>());
  return hi;
}

// Judged against the boxes, not the voxels: every sampled region point keeps its foot
// disk plus the 1 cm edge margin on a true top surface (within a voxel in height), and
// regions cover 85 % of what a map can certify of each walkable face (the face inset by
// foot radius + margin + the half voxel of edge uncertainty of a voxelisation, with that
// room from walls too).
void ExpectSoundAndCovering(const TerrainDescription& t, const RegionExtractionResult& result,
                            double foot_radius_m = 0.01, double clearance_m = 1e9) {
  const double margin = foot_radius_m + 0.01;
  const RegionSoundness sound = MeasureSoundness(result.regions, t, margin, kRes);
  EXPECT_EQ(sound.sound, sound.samples) << "unsound point at " << sound.worst_point.transpose();
  CoverageOptions cov;
  cov.inset_m = cov.disk_radius_m = margin + 0.5 * kRes;
  cov.clearance_m = clearance_m;
  cov.height_tolerance_m = kRes;
  for (const FaceCoverage& c : TopFaceCoverage(result.regions, t, cov)) {
    EXPECT_GE(c.coverage, 0.85) << "face " << c.name;
  }
}

TEST(RegionExtractorTest, FlatGroundIsOneRegionInsetByFootRadiusMarginAndAVoxel) {
  const RegionExtractionResult result = Extract(FlatTerrain());
  ASSERT_EQ(result.regions.size(), 1u);
  const ConvexRegion& r = result.regions[0];
  EXPECT_NEAR(r.SlopeRad(), 0.0, kEps);
  EXPECT_NEAR(r.HeightAt(0.3, -0.2), 0.0, kEps);
  // The 2 m square inset by foot radius 1 cm + edge margin 1 cm + half a 2 cm voxel (a
  // voxelised box's true edge lies within half a voxel of its cells).
  EXPECT_NEAR(Min(r).x(), -0.97, kEps);
  EXPECT_NEAR(Max(r).y(), 0.97, kEps);
  EXPECT_NEAR(r.area_m2, 1.94 * 1.94, 1e-6);
  EXPECT_NEAR(r.plane_tolerance_m, 0.5 * kRes, kEps);
  EXPECT_EQ(r.A.rows(), 6);  // four edges and the plane as two inequalities
  EXPECT_TRUE(result.message.empty());
}

TEST(RegionExtractorTest, LargerFootRadiusInsetsExactly) {
  const RegionExtractionResult result = Extract(FlatTerrain(), 0.05);
  ASSERT_EQ(result.regions.size(), 1u);
  EXPECT_NEAR(Min(result.regions[0]).x(), -0.93, kEps);
  EXPECT_NEAR(Max(result.regions[0]).x(), 0.93, kEps);
}

TEST(RegionExtractorTest, StepGivesTwoRegionsThatStopShortOfTheEdge) {
  const TerrainDescription t = StepTerrain();
  const RegionExtractionResult result = Extract(t);
  ASSERT_EQ(result.regions.size(), 2u);
  int low = 0, high = 0;
  for (const ConvexRegion& r : result.regions) {
    if (std::abs(r.HeightAt(0, 0)) < kEps) {
      ++low;
      EXPECT_NEAR(Max(r).x(), -0.03, kEps);
    } else {
      ++high;
      EXPECT_NEAR(r.HeightAt(0.5, 0), 0.1, kEps);
      EXPECT_NEAR(Min(r).x(), 0.03, kEps);
    }
  }
  EXPECT_EQ(low, 1);
  EXPECT_EQ(high, 1);
  ExpectSoundAndCovering(t, result);
}

TEST(RegionExtractorTest, SteppingStonesGiveOneRegionPerStoneAtItsHeight) {
  const TerrainDescription t = SteppingStonesTerrain();
  const RegionExtractionResult result = Extract(t);
  ASSERT_EQ(result.regions.size(), 12u);
  for (const ConvexRegion& r : result.regions) {
    EXPECT_NEAR(r.area_m2, 0.14 * 0.14, 1e-9);
    const Eigen::Vector2d c = 0.5 * (Min(r) + Max(r));
    EXPECT_NEAR(r.HeightAt(c.x(), c.y()), TrueTopHeight(t, c.x(), c.y()), kEps);
  }
  ExpectSoundAndCovering(t, result);
}

TEST(RegionExtractorTest, MaxRegionsKeepsTheLargestAndSaysSo) {
  RegionExtractorOptions options;
  options.foot_radius_m = 0.01;
  options.max_regions = 5;
  const RegionExtractionResult result = ExtractRegionsFromTerrain(SteppingStonesTerrain(), options);
  EXPECT_EQ(result.regions.size(), 5u);
  EXPECT_NE(result.message.find("max_regions"), std::string::npos) << result.message;
  EXPECT_TRUE(Extract(SteppingStonesTerrain()).message.empty());  // all 12 kept: nothing to say
}

TEST(RegionExtractorTest, ThreeDegreeTiltIsOneTiltedRegion) {
  const TerrainDescription t = TiltTerrain(Deg(3), 0.0);
  const RegionExtractionResult result = Extract(t);
  ASSERT_GE(result.regions.size(), 1u);
  EXPECT_NEAR(result.regions[0].SlopeRad(), Deg(3), Deg(0.5));
  ExpectSoundAndCovering(t, result);
}

TEST(RegionExtractorTest, FifteenDegreeYawedTiltIsCoveredInItsOwnFrame) {
  const TerrainDescription t = TiltTerrain(Deg(15), Deg(30));
  const RegionExtractionResult result = Extract(t);
  ASSERT_GE(result.regions.size(), 1u);
  for (const ConvexRegion& r : result.regions) EXPECT_NEAR(r.SlopeRad(), Deg(15), Deg(1));
  ExpectSoundAndCovering(t, result);
}

TEST(RegionExtractorTest, FortyDegreeSlopeIsRejected) {
  const RegionExtractionResult result = Extract(TiltTerrain(Deg(40), 0.0));
  EXPECT_TRUE(result.regions.empty());
  EXPECT_GE(result.stats.patches_too_steep, 1);
  EXPECT_NE(result.message.find("steeper"), std::string::npos) << result.message;
}

TEST(RegionExtractorTest, GapIsNotBridged) {
  const TerrainDescription t = GapTerrain();
  const RegionExtractionResult result = Extract(t);
  ASSERT_EQ(result.regions.size(), 2u);
  for (const ConvexRegion& r : result.regions) {
    const bool left = Max(r).x() < 0;
    EXPECT_TRUE(left ? Max(r).x() <= -0.13 + kEps : Min(r).x() >= 0.13 - kEps);
  }
  ExpectSoundAndCovering(t, result);
}

TEST(RegionExtractorTest, WallSplitsTheGroundAndKeepsFeetOffIt) {
  const TerrainDescription t = WallTerrain();
  const RegionExtractionResult result = Extract(t);
  int ground = 0;
  for (const ConvexRegion& r : result.regions) {
    if (std::abs(r.HeightAt(0, 0)) < kEps) {
      ++ground;
      // The wall occupies |x| <= 0.02; a foot of radius 1 cm keeps the 1 cm margin and
      // the half voxel of edge uncertainty.
      EXPECT_TRUE(Max(r).x() <= -0.05 + kEps || Min(r).x() >= 0.05 - kEps);
    } else {
      ADD_FAILURE() << "the 4 cm wall's top holds no foot with its margin";
    }
  }
  EXPECT_EQ(ground, 2);
  ExpectSoundAndCovering(t, result);
}

TEST(RegionExtractorTest, NonConvexPatchIsCoveredOnlyWhereThereIsSurface) {
  // An L of two boxes at the same height: its hull would include the missing corner.
  TerrainDescription t;
  TerrainBox a, b;
  a.center_world_m = {0.5, 0.1, -0.05};
  a.size_m = {1.0, 0.2, 0.1};
  b.center_world_m = {0.1, 0.6, -0.05};
  b.size_m = {0.2, 0.8, 0.1};
  t.boxes = {a, b};
  const RegionExtractionResult result = Extract(t);
  ASSERT_GE(result.regions.size(), 2u);
  EXPECT_EQ(result.stats.patches, 1);
  EXPECT_LE(MaxDistanceToTopSurfaceM(result.regions, t, 0.0), kEps);
  EXPECT_EQ(FindRegionBelow(result.regions, 0.6, 0.6, 0.0), -1);  // the missing corner
}

TEST(RegionExtractorTest, EmptyMapHasNoRegionsAndSaysSo) {
  OccupancyMap empty;
  empty.resolution_m = kRes;
  const RegionExtractionResult result = ExtractRegions(empty, RegionExtractorOptions());
  EXPECT_TRUE(result.regions.empty());
  EXPECT_NE(result.message.find("no occupied voxels"), std::string::npos);
}

bool SameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

// The fit, the segmentation and the decomposition run on options.threads threads; the
// regions, their order, the statistics and every cell's fate are those of one thread, with
// max_regions cutting the patches short too.
void ExpectSameOnThreads(const TerrainDescription& terrain, int max_regions) {
  RegionExtractorOptions options;
  options.foot_radius_m = 0.01;
  options.max_regions = max_regions;
  options.record_cell_fates = true;
  options.threads = 1;
  const RegionExtractionResult one = ExtractRegionsFromTerrain(terrain, options);
  ASSERT_FALSE(one.regions.empty());
  for (int threads : {2, 3}) {
    options.threads = threads;
    const RegionExtractionResult many = ExtractRegionsFromTerrain(terrain, options);
    ASSERT_EQ(many.regions.size(), one.regions.size()) << threads << " threads";
    for (size_t i = 0; i < one.regions.size(); ++i) {
      EXPECT_EQ(many.regions[i].vertices_world_m, one.regions[i].vertices_world_m) << "region " << i;
    }
    EXPECT_EQ(many.region_layer, one.region_layer);
    EXPECT_EQ(many.cell_fates, one.cell_fates);
    EXPECT_EQ(many.message, one.message);
    EXPECT_EQ(many.stats.patches, one.stats.patches);
    EXPECT_EQ(many.stats.patches_too_small, one.stats.patches_too_small);
    EXPECT_EQ(many.stats.patches_too_steep, one.stats.patches_too_steep);
    // The layers' repaired heights and the cells the repair moved, bit for bit (NaN too).
    ASSERT_EQ(many.layers.size(), one.layers.size());
    for (size_t l = 0; l < one.layers.size(); ++l) {
      EXPECT_TRUE(SameBits(many.layers[l].height_m, one.layers[l].height_m)) << "layer " << l;
    }
    ASSERT_EQ(many.moved_as_seen.size(), one.moved_as_seen.size());
    for (size_t l = 0; l < one.moved_as_seen.size(); ++l) {
      EXPECT_TRUE(SameBits(many.moved_as_seen[l].height_m, one.moved_as_seen[l].height_m)) << "layer " << l;
    }
  }
}

TEST(RegionExtractorTest, RegionsDoNotDependOnTheThreads) {
  ExpectSameOnThreads(SteppingStonesTerrain(), 4096);
  ExpectSameOnThreads(SteppingStonesTerrain(), 5);  // the cap inside the patch list
  ExpectSameOnThreads(TableTerrain(), 4096);        // two layers
  ExpectSameOnThreads(TiltTerrain(Deg(15), Deg(30)), 3);
  // A grid of more than 2^16 cells and a layer of more than 8192 surface cells: the layer
  // passes run in several bands of rows and the fit in several parts; with scan noise
  // (voxels a voxel off, holes) for the repair and the noise levels to change.
  TerrainDescription building = BuildingFloorTerrain();
  building.noise.seed = 3;
  building.noise.jitter_fraction = 0.03;
  building.noise.hole_fraction = 0.01;
  building.noise.outliers = 20;
  ExpectSameOnThreads(building, 4096);
}

TEST(ParallelForTest, RunsEveryItemOnceAndRethrowsTheFirstError) {
  for (int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> runs(100);
    ParallelFor(100, threads, [&](int i) { ++runs[static_cast<size_t>(i)]; });
    for (const std::atomic<int>& r : runs) EXPECT_EQ(r.load(), 1) << threads << " threads";
  }
  for (int threads : {1, 2}) {
    std::atomic<int> started{0};
    EXPECT_THROW(ParallelFor(1000, threads,
                             [&](int i) {
                               ++started;
                               if (i == 3) throw std::runtime_error("item 3");
                             }),
                 std::runtime_error);
    if (threads == 1) {
      EXPECT_EQ(started.load(), 4);  // no item starts after an error
    }
  }
}

TEST(RegionExtractorTest, RejectsOptionsOutOfRange) {
  RegionExtractorOptions options;
  options.foot_radius_m = -0.1;
  try {
    ExtractRegions(VoxelizeTerrain(FlatTerrain()), options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("foot_radius_m"), std::string::npos);
  }
  options = RegionExtractorOptions();
  options.max_slope_rad = 2.0;
  EXPECT_THROW(ExtractRegions(VoxelizeTerrain(FlatTerrain()), options), InputError);
  options = RegionExtractorOptions();
  options.threads = 0;
  EXPECT_THROW(ExtractRegions(VoxelizeTerrain(FlatTerrain()), options), InputError);
}

TEST(RegionExtractorTest, CourseRegionsAreSoundAndCoverEveryFlatFace) {
  const TerrainDescription t = CourseTerrain4m();
  const RegionExtractionResult result = Extract(t);
  EXPECT_GE(result.stats.patches_too_steep, 1);  // the 40 degree ramp
  for (const ConvexRegion& r : result.regions) EXPECT_LE(r.SlopeRad(), 0.45);
  ExpectSoundAndCovering(t, result);
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

// Six 0.4 m x 2 m slabs at 2 cm, relabelled as finer cells: the same tree, but a 1 cm foot
// spans 201^2 cells of 0.1 mm per fit. Refused up front with a message naming the resolution.
OccupancyMap FineStones(double resolution_m) {
  TerrainDescription t;
  t.resolution_m = 0.02;
  for (int i = 0; i < 6; ++i) {
    TerrainBox b;
    b.center_world_m = Eigen::Vector3d(0.42 * i, 0.0, -0.05 + 0.01 * i);
    b.size_m = Eigen::Vector3d(0.4, 2.0, 0.1);  // 6 x 20 x 100 cells of surface
    t.boxes.push_back(b);
  }
  OccupancyMap map = VoxelizeTerrain(t);
  const double scale = resolution_m / map.resolution_m;
  map.resolution_m = resolution_m;
  for (auto& leaf : map.leaves) {
    leaf.center_world_m *= scale;
    leaf.size_m *= scale;
  }
  return map;
}

TEST(RegionExtractorLimits, AMapFarFinerThanTheFootIsRefusedNamingItsResolution) {
  RegionExtractorOptions options;
  options.foot_radius_m = 0.01;
  try {
    ExtractRegions(FineStones(1e-4), options);
    ADD_FAILURE() << "a 0.1 mm map was extracted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("resolution 0.0001 m is too fine"), std::string::npos) << e.what();
  }
  // The same map at 2 cm: extracted.
  EXPECT_FALSE(ExtractRegions(FineStones(0.02), options).regions.empty());
}

TEST(RegionExtractorLimits, AnExpiredDeadlineEndsTheExtractionWithAMessage) {
  RegionExtractorOptions options;
  options.deadline = Deadline::After(0.0);
  const RegionExtractionResult r = ExtractRegions(FineStones(0.02), options);
  EXPECT_TRUE(r.stopped);
  EXPECT_TRUE(r.regions.empty());
  EXPECT_NE(r.message.find("time limit"), std::string::npos) << r.message;
  std::atomic<bool> stop{false};
  options.deadline = Deadline().WithStop(&stop);
  EXPECT_FALSE(ExtractRegions(FineStones(0.02), options).stopped);
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

// A 3 m x 3 m floor at 2 cm with a one-voxel hole every 0.2 m (its column drops to ground
// 0.4 m below): one patch with 196 holes, each inset by foot + margin + half a voxel.
OccupancyMap FloorWithHoles(std::vector<Eigen::Vector2d>* holes) {
  TerrainDescription t;
  t.resolution_m = 0.02;
  TerrainBox floor, ground;
  floor.center_world_m = Eigen::Vector3d(1.5, 1.5, -0.03);
  floor.size_m = Eigen::Vector3d(3.0, 3.0, 0.06);
  ground.center_world_m = Eigen::Vector3d(1.5, 1.5, -0.45);
  ground.size_m = Eigen::Vector3d(3.0, 3.0, 0.1);
  t.boxes = {floor, ground};
  OccupancyMap map = VoxelizeTerrain(t);
  for (int i = 1; i < 15; ++i) {
    for (int j = 1; j < 15; ++j) holes->emplace_back(0.2 * i + 0.01, 0.2 * j + 0.01);  // voxel centres
  }
  auto in_hole = [&](const OccupiedLeaf& leaf) {
    if (leaf.center_world_m.z() < -0.2) return false;
    for (const Eigen::Vector2d& h : *holes) {
      if ((leaf.center_world_m.head<2>() - h).cwiseAbs().maxCoeff() < 0.005) return true;
    }
    return false;
  };
  map.leaves.erase(std::remove_if(map.leaves.begin(), map.leaves.end(), in_hole), map.leaves.end());
  return map;
}

struct FloorCover {
  int regions = 0;
  double area_m2 = 0.0;
  int unsound = 0;  // sampled points closer than foot + margin to a hole
};

// Regions on the floor (height 0) and their area; every sampled point keeps foot + margin
// from every hole's square.
FloorCover CoverFloorWithHoles(double regions_per_m2, RegionExtractionResult* out = nullptr) {
  std::vector<Eigen::Vector2d> holes;
  RegionExtractorOptions options;
  options.foot_radius_m = 0.01;
  options.edge_uncertainty_voxels = 0.5;  // a voxelisation
  options.regions_per_m2 = regions_per_m2;
  options.record_cell_fates = out != nullptr;
  RegionExtractionResult result = ExtractRegions(FloorWithHoles(&holes), options);
  FloorCover cover;
  const double step = 0.004, keep = 0.02 - 1e-9;
  for (const ConvexRegion& r : result.regions) {
    if (std::abs(r.HeightAt(Min(r).x(), Min(r).y())) > 0.01) continue;
    ++cover.regions;
    const Eigen::Vector2d lo = Min(r), hi = Max(r);
    for (double x = lo.x() + 0.5 * step; x < hi.x(); x += step) {
      for (double y = lo.y() + 0.5 * step; y < hi.y(); y += step) {
        if (PlanDistanceToRegion(r, {x, y}) > 0.0) continue;
        cover.area_m2 += step * step;
        for (const Eigen::Vector2d& h : holes) {
          const Eigen::Vector2d d = ((Eigen::Vector2d(x, y) - h).cwiseAbs().array() - 0.01).max(0.0);
          if (d.norm() < keep && ++cover.unsound == 1) {
            ADD_FAILURE() << "region " << r.id << " point (" << x << ", " << y << ") near hole " << h.transpose();
          }
        }
      }
    }
  }
  if (out != nullptr) *out = std::move(result);
  return cover;
}

TEST(RegionExtractorCover, AFloorWithScatteredHolesGetsRegionsInProportionToItsArea) {
  const FloorCover fixed = CoverFloorWithHoles(0.0);  // 24 regions per patch at most
  const FloorCover sized = CoverFloorWithHoles(8.0);  // up to 72 for the 9 m^2 patch
  EXPECT_LE(fixed.regions, 24);
  EXPECT_GT(sized.regions, 24);
  EXPECT_LE(sized.regions, 72);
  EXPECT_EQ(fixed.unsound + sized.unsound, 0);
  // What a foot centre may use: the floor inset by 3 cm (foot, margin, half a voxel) at
  // its border and from each hole's square.
  const double usable_m2 = 2.94 * 2.94 - 196 * (0.02 * 0.02 + 4 * 0.02 * 0.03 + M_PI * 0.03 * 0.03);
  EXPECT_LT(fixed.area_m2, 0.85 * usable_m2);
  EXPECT_GT(sized.area_m2, fixed.area_m2 + 0.05 * usable_m2);
}

TEST(RegionExtractorCover, TheDefaultCapCoversMoreOfAHoledFloorThanFourRegionsPerSquareMetre) {
  // Four per m^2 stopped a scanned lab's floor at its cap (docs/measurements.md, stop 32):
  // the default lets the 9 m^2 patch hold more regions, each of them sound.
  const FloorCover four = CoverFloorWithHoles(4.0);
  const FloorCover by_default = CoverFloorWithHoles(RegionExtractorOptions{}.regions_per_m2);
  EXPECT_LE(four.regions, 36);
  EXPECT_GT(by_default.regions, four.regions);
  EXPECT_GT(by_default.area_m2, four.area_m2);
  EXPECT_EQ(four.unsound + by_default.unsound, 0);
}

TEST(RegionExtractorCover, CellFatesSayWhatBecameOfEachFloorCell) {
  RegionExtractionResult result;
  CoverFloorWithHoles(8.0, &result);
  ASSERT_EQ(result.cell_fates.size(), result.layers.size());
  const HeightMap& hm = result.layers.front();
  auto fate_at = [&](double x, double y) {
    const int col = static_cast<int>(std::floor((x - hm.origin_world_m.x()) / hm.resolution_m));
    const int row = static_cast<int>(std::floor((y - hm.origin_world_m.y()) / hm.resolution_m));
    return result.cell_fates[0][static_cast<size_t>(hm.Index(row, col))];
  };
  EXPECT_NE(fate_at(1.01, 1.01), CellFate::kCovered);           // a hole
  EXPECT_EQ(fate_at(1.03, 1.01), CellFate::kInsetOffPatch);     // beside it
  EXPECT_EQ(fate_at(1.11, 1.11), CellFate::kCovered);           // between four holes
  EXPECT_EQ(fate_at(0.01, 1.51), CellFate::kInsetOffPatch);     // at the floor's border
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

// A half-ring walkway 0.6 m wide of 12 boxes rotated to the arc's tangent, meeting at the
// outer edge (issue 29's ring), top at z = 0.
TerrainDescription HalfRingWalkway() {
  TerrainDescription terrain;
  const int n = 12;
  const double mid = 1.2, width = 0.6, length = 2 * (mid + width / 2) * std::tan(M_PI / (2 * n));
  for (int k = 0; k < n; ++k) {
    const double a = (k + 0.5) * M_PI / n;
    TerrainBox box;
    box.center_world_m = Eigen::Vector3d(mid * std::cos(a), mid * std::sin(a), -0.05);
    box.size_m = Eigen::Vector3d(length, width, 0.1);
    box.rpy_rad = Eigen::Vector3d(0, 0, a + M_PI / 2);
    terrain.boxes.push_back(box);
  }
  return terrain;
}

// Share of the ring's certifiable surface (foot + margin + half a voxel inside the true
// surface, sampled every 2 cm) inside a region at the surface's height.
double RingCoverage(const TerrainDescription& ring, const std::vector<ConvexRegion>& regions, double margin_m) {
  long surface = 0, covered = 0;
  for (double x = -1.6; x <= 1.6; x += 0.02) {
    for (double y = -0.1; y <= 1.6; y += 0.02) {
      if (!FootOnTrueSurface(ring, {x, y, 0.0}, margin_m, 0.5, 1e-3)) continue;
      ++surface;
      const int r = FindRegionBelow(regions, x, y, 0.0);
      if (r >= 0 && std::abs(regions[static_cast<size_t>(r)].HeightAt(x, y)) < kRes) ++covered;
    }
  }
  return surface > 0 ? double(covered) / surface : 0.0;
}

// Issue 29: convex pieces follow the ring's curve where rectangles leave its outer and
// inner edges in steps; both stay on the true surface.
TEST(RegionExtractorCover, ARingWalkwayIsCoveredByConvexPiecesAlongItsCurve) {
  const TerrainDescription ring = HalfRingWalkway();
  const double foot = 0.01, margin = foot + 0.01;
  double share[2] = {0.0, 0.0};
  size_t count[2] = {0, 0};
  for (const bool convex : {false, true}) {
    RegionExtractorOptions options;
    options.foot_radius_m = foot;
    options.max_slope_rad = 0.45;
    options.convex_cover = convex;
    const RegionExtractionResult result = ExtractRegionsFromTerrain(ring, options);
    const RegionSoundness sound = MeasureSoundness(result.regions, ring, margin, kRes);
    EXPECT_EQ(sound.sound, sound.samples) << "convex " << convex << ": unsound point at " << sound.worst_point.transpose();
    share[convex] = RingCoverage(ring, result.regions, margin + 0.5 * kRes);
    count[convex] = result.regions.size();
  }
  std::printf("ring walkway: rectangles %zu regions cover %.1f %%, convex pieces %zu regions cover %.1f %%\n", count[0],
              100 * share[0], count[1], 100 * share[1]);
  EXPECT_GT(share[1], share[0]);
}

// A patch of convex_alone_cells kept cells or more is covered by the convex pieces without
// rectangles to compare them with: on the ring, where the pieces win the comparison, the
// regions are the compared cover's, and they stay on the true surface either way.
TEST(RegionExtractorCover, ALargePatchIsCoveredByThePiecesAloneAsByTheComparison) {
  const TerrainDescription ring = HalfRingWalkway();
  const double foot = 0.01, margin = foot + 0.01;
  std::vector<ConvexRegion> regions[2];
  int patches_alone[2] = {0, 0};
  for (const bool alone : {false, true}) {
    RegionExtractorOptions options;
    options.foot_radius_m = foot;
    options.max_slope_rad = 0.45;
    options.convex_alone_cells = alone ? 0 : std::numeric_limits<int>::max();
    options.convex_alone_outline = 0.0;  // any outline
    options.convex_alone_outline_share = 0.0;
    const RegionExtractionResult result = ExtractRegionsFromTerrain(ring, options);
    regions[alone] = result.regions;
    patches_alone[alone] = result.stats.patches_convex_alone;
    const RegionSoundness sound = MeasureSoundness(regions[alone], ring, margin, kRes);
    EXPECT_EQ(sound.sound, sound.samples) << "alone " << alone << ": unsound point at " << sound.worst_point.transpose();
  }
  // The path taken: no patch alone when every patch compares, every decomposed patch alone
  // (the ring's walkway at least) when convex_alone_cells is 0.
  EXPECT_EQ(patches_alone[0], 0);
  EXPECT_GE(patches_alone[1], 1);
  ASSERT_EQ(regions[0].size(), regions[1].size());
  for (size_t i = 0; i < regions[0].size(); ++i) {
    EXPECT_EQ(regions[0][i].vertices_world_m, regions[1][i].vertices_world_m) << "region " << i;
  }
}

}  // namespace
}  // namespace mfp
