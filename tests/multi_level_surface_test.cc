// Surfaces above one another, maps built from sensor rays, and scan noise: regions only
// where a foot can really stand, judged against the boxes the maps were made from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "terrain/extraction/internal/surface_layers.h"
#include "terrain/extraction/map_simulation.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/quality/terrain_catalogue.h"
#include "terrain/quality/terrain_quality.h"

namespace mfp {
namespace {

RegionExtractionResult Extract(const TerrainDescription& t, double clearance_m, double foot_radius_m = 0.01) {
  RegionExtractorOptions options;
  options.foot_radius_m = foot_radius_m;
  options.clearance_m = clearance_m;
  return ExtractRegionsFromTerrain(t, options);
}

int CountRegionsAt(const std::vector<ConvexRegion>& regions, double z_m, double tol_m) {
  int n = 0;
  for (const ConvexRegion& r : regions) {
    const Eigen::Vector3d& v = r.vertices_world_m.front();
    n += std::abs(r.HeightAt(v.x(), v.y()) - z_m) <= tol_m;
  }
  return n;
}

void ExpectSound(const TerrainDescription& t, const RegionExtractionResult& result, double foot_radius_m) {
  const RegionSoundness s = MeasureSoundness(result.regions, t, foot_radius_m + 0.01, t.resolution_m);
  EXPECT_EQ(s.sound, s.samples) << "unsound point at " << s.worst_point.transpose();
}

// Coverage of a face's part a map can certify (inset by foot radius + 1 cm margin + a
// voxel), or with whole_face of all of its walkable part (foot radius + margin only).
double FaceCoverageOf(const std::vector<ConvexRegion>& regions, const TerrainDescription& t,
                      const std::string& face, double clearance_m, double foot_radius_m,
                      bool whole_face = false) {
  CoverageOptions cov;
  cov.inset_m = cov.disk_radius_m = foot_radius_m + 0.01 + (whole_face ? 0.0 : t.resolution_m);
  cov.clearance_m = clearance_m;
  cov.height_tolerance_m = t.resolution_m;
  cov.only_face = face;
  for (const FaceCoverage& c : TopFaceCoverage(regions, t, cov)) {
    if (c.name == face) return c.coverage;
  }
  ADD_FAILURE() << "no face " << face;
  return 0.0;
}

TEST(MultiLevelSurfaceTest, GroundUnderABridgeAppearsWithTheClearance) {
  const TerrainDescription t = BridgeTerrain();
  // Highest surfaces only (no clearance given): the deck hides the ground under it.
  const RegionExtractionResult top = Extract(t, INFINITY);
  EXPECT_EQ(top.stats.layers, 1);
  EXPECT_EQ(FindRegionBelow(top.regions, 0.0, 0.0, 0.0), FindRegionBelow(top.regions, 0.0, 0.5, 0.0));
  // 0.4 m of clearance: the ground under the 0.5 m high deck is a second level.
  const RegionExtractionResult both = Extract(t, 0.4);
  EXPECT_EQ(both.stats.layers, 2);
  EXPECT_GE(CountRegionsAt(both.regions, 0.6, 1e-6), 1);
  EXPECT_GE(CountRegionsAt(both.regions, 0.0, 1e-6), 1);
  EXPECT_GE(FaceCoverageOf(both.regions, t, "ground", 0.4, 0.01), 0.85);
  EXPECT_GE(FaceCoverageOf(both.regions, t, "bridge", 0.4, 0.01), 0.85);
  ExpectSound(t, both, 0.01);
  // A robot needing 0.6 m does not fit under the deck.
  const RegionExtractionResult tall = Extract(t, 0.6);
  EXPECT_LT(FaceCoverageOf(tall.regions, t, "ground", 0.4, 0.01), 0.8);
}

TEST(MultiLevelSurfaceTest, FloorUnderATableAndTreadsUnderAnOverhang) {
  for (const TerrainDescription& t : {TableTerrain(), OverhangTerrain()}) {
    const RegionExtractionResult result = Extract(t, 0.4);
    EXPECT_EQ(result.stats.layers, 2);
    ExpectSound(t, result, 0.01);
    for (const char* face : {"floor", "ground", "tread1", "tread2", "table", "overhang"}) {
      bool has = false;
      for (const TerrainBox& b : t.boxes) has = has || b.name == face;
      if (has) {
        EXPECT_GE(FaceCoverageOf(result.regions, t, face, 0.4, 0.01), 0.85) << face;
      }
    }
  }
}

TEST(MultiLevelSurfaceTest, AtOneCentimetreStonesTiltsAndBridgeCoverTheirWholeWalkableFaces) {
  // The criterion: soundness against the boxes and 85 % of each walkable face
  // (inset by foot radius + margin only). At 2 cm the half voxel of edge uncertainty a
  // side leaves 77 % of a 20 cm stone's; at 1 cm 88 %.
  std::vector<std::pair<TerrainDescription, std::vector<std::string>>> maps = {
      {SteppingStonesTerrain(), {"stone00", "stone01", "stone02", "stone10", "stone11", "stone12", "stone20",
                                 "stone21", "stone22", "stone30", "stone31", "stone32"}},
      {TiltTerrain(15 * M_PI / 180, M_PI / 6), {"tilted"}},
      {BridgeTerrain(), {"ground", "bridge"}}};
  for (auto& [t, faces] : maps) {
    t.resolution_m = 0.01;
    const RegionExtractionResult result = Extract(t, 0.4);
    ExpectSound(t, result, 0.01);
    for (const std::string& face : faces) {
      EXPECT_GE(FaceCoverageOf(result.regions, t, face, 0.4, 0.01, true), 0.85) << face;
    }
  }
}

TEST(MultiLevelSurfaceTest, PointFeetKeepTheMarginOnStonesAndTilts) {
  // Foot radius 0: the edge margin and the voxel of edge uncertainty still hold.
  for (const TerrainDescription& t : {SteppingStonesTerrain(), TiltTerrain(15 * M_PI / 180, M_PI / 6)}) {
    const RegionExtractionResult result = Extract(t, INFINITY, 0.0);
    ASSERT_FALSE(result.regions.empty());
    ExpectSound(t, result, 0.0);
  }
}

TEST(MultiLevelSurfaceTest, ScannedCorridorHasNoRegionOnItsCeilingAndKeepsItsNoisyFloor) {
  MapNoise noise;
  noise.seed = 3;
  noise.jitter_fraction = 0.03;
  noise.hole_fraction = 0.01;
  noise.outliers = 20;
  // Seed 3 is the worst of seeds 1-5 for floor coverage (86.5 %; the others 89-91 %).
  const TerrainDescription t = CorridorTerrain(7.0, 0.08, noise);
  const OccupancyMap map = MakeTerrainMap(t);
  ASSERT_FALSE(map.free_leaves.empty());
  RegionExtractorOptions options;
  options.clearance_m = 0.5;
  const RegionExtractionResult result = ExtractRegions(map, options);
  ASSERT_FALSE(result.regions.empty());
  EXPECT_GT(result.stats.not_seen_from_above, 0);  // the ceiling's top
  EXPECT_EQ(result.stats.isolated_voxels, 20);     // every outlier, and none made a region
  for (const ConvexRegion& r : result.regions) {
    // On the floor (the noise tilts a fit by less than a quarter voxel).
    for (const Eigen::Vector3d& v : r.vertices_world_m) EXPECT_NEAR(v.z(), 0.0, 0.02);
  }
  ExpectSound(t, result, options.foot_radius_m);
  EXPECT_GE(FaceCoverageOf(result.regions, t, "floor", 0.5, options.foot_radius_m), 0.85);
  // Told the map is a scan (no wall reaches into a floor voxel: its voxel above would be
  // hit), the floor keeps no edge uncertainty at the walls. Of the whole floor (inset by
  // foot radius + margin only) this seed's regions cover 83.5 % (its 1 % of missed
  // voxels are drops, each inset by a voxel); seed 7 in mfp-terrain-bench 91 %.
  options.riser_uncertainty_voxels = 0.0;
  const RegionExtractionResult scan = ExtractRegions(map, options);
  ExpectSound(t, scan, options.foot_radius_m);
  EXPECT_GE(FaceCoverageOf(scan.regions, t, "floor", 0.5, options.foot_radius_m, true), 0.8);
  // Without the seen-from-above test the ceiling's top comes back.
  options.require_seen_from_above = false;
  // (The scan sees the ceiling from below only: its one voxel layer ends at 2.88 m.)
  EXPECT_GT(CountRegionsAt(ExtractRegions(map, options).regions, 2.88, 0.02), 0);
}

TEST(MultiLevelSurfaceTest, SingleCellNoiseIsUndoneButEdgesAreNot) {
  HeightMap hm;
  hm.resolution_m = 0.1;
  hm.rows = hm.cols = 5;
  hm.height_m.assign(25, 0.0f);
  hm.height_m[hm.Index(2, 2)] = NAN;   // a hole inside
  hm.height_m[hm.Index(1, 3)] = 0.1f;  // a cell one voxel up
  hm.height_m[hm.Index(0, 0)] = NAN;   // a missing corner stays missing
  hm.height_m[hm.Index(4, 4)] = 0.3f;  // three voxels up, on the border: kept
  int changed = FillSingleCellNoise(&hm);
  changed += FillSingleCellNoise(&hm);
  EXPECT_EQ(changed, 2);
  EXPECT_EQ(hm.height_m[hm.Index(2, 2)], 0.0f);
  EXPECT_EQ(hm.height_m[hm.Index(1, 3)], 0.0f);
  EXPECT_TRUE(std::isnan(hm.height_m[hm.Index(0, 0)]));
  EXPECT_EQ(hm.height_m[hm.Index(4, 4)], 0.3f);
  // A cell three voxels off its neighbours is a real object, not noise.
  hm.height_m[hm.Index(2, 2)] = 0.3f;
  EXPECT_EQ(FillSingleCellNoise(&hm), 0);
}

TEST(MultiLevelSurfaceTest, TruthTestSeesFloorsUnderDecksAndRejectsEdges) {
  const TerrainDescription t = BridgeTerrain();
  EXPECT_TRUE(OnTrueTopSurface(t, {0.0, 0.0, 0.0}, 0.02, 0.02));    // ground under the deck
  EXPECT_TRUE(OnTrueTopSurface(t, {0.0, 0.0, 0.6}, 0.02, 0.02));    // the deck
  EXPECT_FALSE(OnTrueTopSurface(t, {0.0, 0.0, 0.3}, 0.02, 0.02));   // in between
  EXPECT_FALSE(OnTrueTopSurface(t, {0.29, 0.0, 0.6}, 0.02, 0.02));  // disk over the deck's edge
  EXPECT_FALSE(OnTrueTopSurface(t, {0.0, 0.9, 0.0}, 0.02, 0.02));   // inside a pier
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

// The corridor: floor, walls with doors, ceiling, free space from rays, floors
// noisy by a voxel (3 % of floor columns one voxel off) and 20 outlier voxels, 8 cm. On
// each of ten noise seeds the regions cover at least 84 % of the whole walkable floor
// (inset by foot radius + margin only). A column jittered down is an erased cell (a ray
// freed the floor's voxel): no foot disk may reach it, which costs 0.5-2.8 points of this
// floor (docs/measurements.md, issue 25, stop 35). (Missed floor voxels, the test above,
// are drops and cost more: 83.5-91 % with 1 % of them.)
TEST(MultiLevelSurfaceTest, ScannedCorridorWithAVoxelOfNoiseCoversItsWholeFloor) {
  for (uint32_t seed = 1; seed <= 10; ++seed) {
    MapNoise noise;
    noise.seed = seed;
    noise.jitter_fraction = 0.03;
    noise.outliers = 20;
    const TerrainDescription t = CorridorTerrain(7.0, 0.08, noise);
    RegionExtractorOptions options;
    options.clearance_m = 0.5;
    options.riser_uncertainty_voxels = 0.0;  // a scan: no wall reaches into a floor voxel
    const RegionExtractionResult scan = ExtractRegions(MakeTerrainMap(t), options);
    ExpectSound(t, scan, options.foot_radius_m);
    EXPECT_GE(FaceCoverageOf(scan.regions, t, "floor", 0.5, options.foot_radius_m, true), 0.84) << "seed " << seed;
  }
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

// A scanned floor of n x n columns of 5 cm voxels, its top at z = 0, rays having freed the
// 12 voxels above it. Columns listed in `unseen` hold nothing and no ray reached their
// floor voxel (only the voxels from 5 cm up are free); those in `erased` have their floor
// voxel freed by a ray and nothing under it; those in `raised` have their top a voxel up.
struct ScanFloor {
  int n = 15;
  std::vector<std::pair<int, int>> unseen, erased, raised;
  OccupancyMap Map() const {
    const double r = 0.05;
    OccupancyMap map;
    map.resolution_m = r;
    auto has = [](const std::vector<std::pair<int, int>>& list, int i, int j) {
      return std::find(list.begin(), list.end(), std::make_pair(i, j)) != list.end();
    };
    auto voxel = [r](int i, int j, int k) { return OccupiedLeaf{{(i + 0.5) * r, (j + 0.5) * r, (k + 0.5) * r}, r}; };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const bool empty = has(unseen, i, j) || has(erased, i, j);
        const int top = has(raised, i, j) ? 0 : -1;  // voxel index of the top
        if (!empty) {
          for (int k = -3; k <= top; ++k) map.leaves.push_back(voxel(i, j, k));
        }
        for (int k = has(unseen, i, j) ? 1 : (has(erased, i, j) ? -1 : top + 1); k <= 12; ++k) {
          map.free_leaves.push_back(voxel(i, j, k));
        }
      }
    }
    return map;
  }
};

SurfaceLayers ScanLayers(const ScanFloor& floor, int radius_cells) {
  SurfaceLayerOptions options;
  options.clearance_m = 0.4;
  options.step_gate_m = 0.06;
  options.enclosed_unseen_radius_cells = radius_cells;
  return BuildSurfaceLayers(floor.Map(), options);
}

std::vector<std::pair<int, int>> Block(int i0, int j0, int size) {
  std::vector<std::pair<int, int>> cells;
  for (int i = i0; i < i0 + size; ++i) {
    for (int j = j0; j < j0 + size; ++j) cells.emplace_back(i, j);
  }
  return cells;
}

float HeightAt(const SurfaceLayers& layers, int i, int j) {
  const HeightMap& layer = layers.layers.front();
  const int col = static_cast<int>(std::floor(((i + 0.5) * 0.05 - layer.origin_world_m.x()) / 0.05));
  const int row = static_cast<int>(std::floor(((j + 0.5) * 0.05 - layer.origin_world_m.y()) / 0.05));
  return layer.height_m[static_cast<size_t>(layer.Index(row, col))];
}

// docs/unseen_floor.md: a 3 x 3 block of floor nobody saw, seen floor of one height all
// round within 3 cells, is floor at that height; so it is not when the radius is too short,
// nor when rays freed the floor's voxels there (erased), nor when the unseen block reaches
// the map's edge (not enclosed).
TEST(MultiLevelSurfaceTest, UnseenFloorEnclosedBySeenFloorIsFloorButErasedFloorIsNot) {
  ScanFloor floor;
  floor.unseen = Block(6, 6, 3);
  const SurfaceLayers filled = ScanLayers(floor, 3);
  EXPECT_EQ(filled.enclosed_unseen_filled, 9);
  for (const auto& [i, j] : floor.unseen) EXPECT_EQ(HeightAt(filled, i, j), 0.0f) << i << ", " << j;
  EXPECT_EQ(ScanLayers(floor, 1).enclosed_unseen_filled, 0);  // the centre sees no floor within one cell
  EXPECT_EQ(ScanLayers(floor, 0).enclosed_unseen_filled, 0);

  ScanFloor erased;
  erased.erased = Block(6, 6, 3);
  const SurfaceLayers not_filled = ScanLayers(erased, 3);
  EXPECT_EQ(not_filled.enclosed_unseen_filled, 0);
  EXPECT_TRUE(std::isnan(HeightAt(not_filled, 7, 7)));

  ScanFloor at_edge;
  at_edge.unseen = Block(0, 6, 3);
  EXPECT_EQ(ScanLayers(at_edge, 3).enclosed_unseen_filled, 0);
}

// SurfaceLayers::filled says why a cell empty in the map holds a surface: unseen floor (no
// ray reached its floor voxel: a single cell or an enclosed block) or erased floor (a ray
// passed through that voxel, nothing under it: a single cell only).
TEST(MultiLevelSurfaceTest, FilledCellsRecordWhetherTheFloorWasUnseenOrErased) {
  ScanFloor floor;
  floor.unseen = Block(6, 6, 3);
  floor.unseen.emplace_back(2, 2);
  floor.erased = {{12, 2}};
  const SurfaceLayers layers = ScanLayers(floor, 3);
  ASSERT_EQ(layers.filled.size(), layers.layers.size());
  const HeightMap& layer = layers.layers.front();
  auto filled_at = [&](int i, int j) {
    const int col = static_cast<int>(std::floor(((i + 0.5) * 0.05 - layer.origin_world_m.x()) / 0.05));
    const int row = static_cast<int>(std::floor(((j + 0.5) * 0.05 - layer.origin_world_m.y()) / 0.05));
    return layers.filled.front()[static_cast<size_t>(layer.Index(row, col))];
  };
  for (const auto& [i, j] : floor.unseen) EXPECT_EQ(filled_at(i, j), kFilledUnseen) << i << ", " << j;
  EXPECT_EQ(filled_at(12, 2), kFilledErased);
  EXPECT_EQ(HeightAt(layers, 12, 2), 0.0f);  // filled all the same, for the plane fit
  EXPECT_EQ(filled_at(4, 4), 0);             // seen floor
}

// A cell the noise repair moves down a voxel keeps its seen height beside the layers: a
// foot standing on that voxel's top stands on seen surface (the fr_079 start foot).
TEST(MultiLevelSurfaceTest, ACellTheNoiseRepairMovesKeepsItsSeenHeight) {
  ScanFloor floor;
  floor.raised = {{7, 7}};
  const SurfaceLayers layers = ScanLayers(floor, 0);
  EXPECT_EQ(HeightAt(layers, 7, 7), 0.0f);  // repaired to the floor's height
  ASSERT_EQ(layers.moved_as_seen.size(), 1u);
  const HeightMap& seen = layers.moved_as_seen.front();
  int moved = 0;
  for (float h : seen.height_m) moved += std::isnan(h) ? 0 : 1;
  EXPECT_EQ(moved, 1);
  const int col = static_cast<int>(std::floor((7.5 * 0.05 - seen.origin_world_m.x()) / 0.05));
  const int row = static_cast<int>(std::floor((7.5 * 0.05 - seen.origin_world_m.y()) / 0.05));
  EXPECT_NEAR(seen.height_m[static_cast<size_t>(seen.Index(row, col))], 0.05f, 1e-6);
}

// A scanned floor with steps, holes, unseen and erased columns, unseen tops, and a slab
// 70 voxels up (the band of voxels asked spans two 64-bit words), its free space as an
// octree would prune it (aligned cubes of 8, 4, 2 and 1 voxels). The known free voxels are
// kept as bits per column of that band, or as runs when the bits would take more memory:
// one occupied voxel 100 000 voxels up (isolated, so dropped, and under no surface) makes
// the band that tall. Both must give the same layers.
OccupancyMap PrunedScanFloor(unsigned seed) {
  const double r = 0.05;
  constexpr int n = 24, k_lo = -8, k_hi = 88;  // free voxels in [-4, 80], cubes aligned from k_lo
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<uint8_t> free_voxel(static_cast<size_t>(n * n * (k_hi - k_lo)), 0);
  auto at = [&](int i, int j, int k) -> uint8_t& { return free_voxel[static_cast<size_t>(((k - k_lo) * n + j) * n + i)]; };
  OccupancyMap map;
  map.resolution_m = r;
  auto leaf = [r](int i, int j, int k, int size) {
    return OccupiedLeaf{{(i + 0.5 * size) * r, (j + 0.5 * size) * r, (k + 0.5 * size) * r}, size * r};
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = u(rng);
      const bool empty = x < 0.12;                                  // unseen (< 0.06) or erased
      const int top = x < 0.3 ? 0 : (x < 0.35 ? 1 : -1);            // voxel index of the top
      const int free_from = x < 0.06 ? 1 : (empty ? -1 : (x > 0.95 ? top + 2 : top + 1));
      if (!empty) {
        for (int k = -3; k <= top; ++k) map.leaves.push_back(leaf(i, j, k, 1));
      }
      const bool slab = i >= 4 && i < 10 && j >= 14 && j < 20;
      if (slab) map.leaves.push_back(leaf(i, j, 69, 1));
      for (int k = std::max(-4, free_from); k <= 80; ++k) at(i, j, k) = !(slab && k == 69);
    }
  }
  std::vector<uint8_t> taken(free_voxel.size(), 0);
  for (int size : {8, 4, 2, 1}) {
    for (int k0 = k_lo; k0 < k_hi; k0 += size) {
      for (int j0 = 0; j0 < n; j0 += size) {
        for (int i0 = 0; i0 < n; i0 += size) {
          bool whole = true;
          for (int k = k0; k < k0 + size; ++k) {
            for (int j = j0; j < j0 + size; ++j) {
              for (int i = i0; i < i0 + size; ++i) whole = whole && at(i, j, k) && !taken[&at(i, j, k) - free_voxel.data()];
            }
          }
          if (!whole) continue;
          for (int k = k0; k < k0 + size; ++k) {
            for (int j = j0; j < j0 + size; ++j) {
              for (int i = i0; i < i0 + size; ++i) taken[&at(i, j, k) - free_voxel.data()] = 1;
            }
          }
          map.free_leaves.push_back(leaf(i0, j0, k0, size));
        }
      }
    }
  }
  return map;
}

void ExpectSameLayers(const SurfaceLayers& a, const SurfaceLayers& b) {
  ASSERT_EQ(a.layers.size(), b.layers.size());
  for (size_t l = 0; l < a.layers.size(); ++l) {
    const std::vector<float>& ha = a.layers[l].height_m;
    const std::vector<float>& hb = b.layers[l].height_m;
    ASSERT_EQ(ha.size(), hb.size());
    EXPECT_EQ(std::memcmp(ha.data(), hb.data(), ha.size() * sizeof(float)), 0) << "layer " << l;
  }
  EXPECT_EQ(a.unseen, b.unseen);
  EXPECT_EQ(a.solid_beside, b.solid_beside);
  EXPECT_EQ(a.filled, b.filled);
  ASSERT_EQ(a.moved_as_seen.size(), b.moved_as_seen.size());
  for (size_t l = 0; l < a.moved_as_seen.size(); ++l) {
    EXPECT_EQ(std::memcmp(a.moved_as_seen[l].height_m.data(), b.moved_as_seen[l].height_m.data(),
                          a.moved_as_seen[l].height_m.size() * sizeof(float)),
              0);
  }
  EXPECT_EQ(a.candidates, b.candidates);
  EXPECT_EQ(a.no_room_above, b.no_room_above);
  EXPECT_EQ(a.not_seen_from_above, b.not_seen_from_above);
  EXPECT_EQ(a.noise_cells_filled, b.noise_cells_filled);
  EXPECT_EQ(a.enclosed_unseen_filled, b.enclosed_unseen_filled);
}

TEST(MultiLevelSurfaceTest, FreeSpaceAsBitsOrAsRunsGivesTheSameLayers) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const OccupancyMap map = PrunedScanFloor(seed);
    OccupancyMap tall = map;
    tall.leaves.push_back(map.leaves.front());  // a floor column's lowest voxel ...
    tall.leaves.back().center_world_m.z() += 1e5 * map.resolution_m;  // ... 100 000 voxels up
    for (int threads : {1, 2, 3}) {
      SurfaceLayerOptions options;
      options.clearance_m = 0.4;
      options.step_gate_m = 0.06;
      options.enclosed_unseen_radius_cells = 3;
      options.threads = threads;
      const SurfaceLayers bits = BuildSurfaceLayers(map, options);
      const SurfaceLayers runs = BuildSurfaceLayers(tall, options);
      SCOPED_TRACE(testing::Message() << "seed " << seed << ", " << threads << " threads");
      // The free space decides things here: tops not seen from above, unseen cells.
      EXPECT_GT(bits.not_seen_from_above, 0);
      EXPECT_GT(bits.layers.size(), 1u);  // the slab over the floor
      size_t unseen_cells = 0;
      for (const std::vector<uint8_t>& u : bits.unseen) unseen_cells += std::count_if(u.begin(), u.end(), [](uint8_t v) { return v != 0; });
      EXPECT_GT(unseen_cells, 0u);
      ExpectSameLayers(bits, runs);
      EXPECT_EQ(runs.isolated_voxels, bits.isolated_voxels + 1);
    }
  }
}

}  // namespace
}  // namespace mfp
