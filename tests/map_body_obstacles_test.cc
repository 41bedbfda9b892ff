// The body's obstacles from an occupancy map (terrain/extraction/map_body_obstacles.h):
// sound (every occupied voxel that may reach a body's band lies in a prism), the floor
// and the surfaces the feet stand on left out, few prisms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "planner/robot/body_clearance.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/map_body_obstacles.h"

namespace mfp {
namespace {

constexpr double kRes = 0.02;  // [m]

struct Voxel {
  int ix, iy, iz;
};

// Voxels ix0..ix1 x iy0..iy1 x iz0..iz1 (inclusive) as single-voxel leaves.
void AddBlock(OccupancyMap* map, std::vector<Voxel>* voxels, int ix0, int ix1, int iy0, int iy1, int iz0, int iz1) {
  for (int ix = ix0; ix <= ix1; ++ix) {
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int iz = iz0; iz <= iz1; ++iz) {
        map->leaves.push_back({Eigen::Vector3d((ix + 0.5) * kRes, (iy + 0.5) * kRes, (iz + 0.5) * kRes), kRes});
        if (voxels != nullptr) voxels->push_back({ix, iy, iz});
      }
    }
  }
}

bool Covered(const std::vector<MapPrism>& prisms, const Voxel& v) {
  const Eigen::Vector3d c((v.ix + 0.5) * kRes, (v.iy + 0.5) * kRes, (v.iz + 0.5) * kRes);
  for (const MapPrism& p : prisms) {
    if (c.x() > p.min_world_m.x() && c.x() < p.max_world_m.x() && c.y() > p.min_world_m.y() &&
        c.y() < p.max_world_m.y() && c.z() > p.bottom_z_m && c.z() < p.top_z_m) {
      return true;
    }
  }
  return false;
}

bool AnyPrismOverColumn(const std::vector<MapPrism>& prisms, int ix, int iy) {
  const Eigen::Vector2d c((ix + 0.5) * kRes, (iy + 0.5) * kRes);
  for (const MapPrism& p : prisms) {
    if ((c.array() > p.min_world_m.array()).all() && (c.array() < p.max_world_m.array()).all()) return true;
  }
  return false;
}

// On a floor whose top is z = 0: a body's band starts floor_band_m above its ground, and
// its ground is at most a voxel below the floor's top.
bool MayReachABand(const Voxel& v, const MapObstacleOptions& options) {
  return (v.iz + 1) * kRes > options.floor_band_m - kRes + 1e-9;
}

MapObstacleOptions Options() {
  MapObstacleOptions o;
  o.floor_band_m = 0.10;
  o.ground_radius_m = 0.10;
  return o;
}

// A 2 m x 1 m floor 4 cm thick (top at z = 0) with a wall, a table on four legs and
// three steps of 4 cm.
TEST(MapBodyObstacles, CoverAWallATableAndItsLegsButNotTheFloorOrTheSteps) {
  OccupancyMap map;
  map.resolution_m = kRes;
  std::vector<Voxel> floor, wall, table, steps;
  AddBlock(&map, &floor, 0, 99, 0, 49, -2, -1);
  AddBlock(&map, &wall, 25, 29, 0, 29, 0, 24);             // x 0.50-0.60, y 0-0.60, 0.5 m high
  AddBlock(&map, &table, 50, 69, 10, 29, 20, 21);          // top 0.40-0.44 m
  for (int lx : {50, 68}) {
    for (int ly : {10, 28}) AddBlock(&map, &table, lx, lx + 1, ly, ly + 1, 0, 19);  // legs
  }
  for (int k = 0; k < 3; ++k) AddBlock(&map, &steps, 80 + 6 * k, 99, 0, 49, 0, 1 + 2 * k);  // tops 0.04, 0.08, 0.12
  const MapObstacles out = MapBodyObstacles(map, Options());
  ASSERT_TRUE(out.complete) << out.message;
  for (const Voxel& v : wall) {
    if (!MayReachABand(v, Options())) continue;
    EXPECT_TRUE(Covered(out.prisms, v)) << v.ix << " " << v.iy << " " << v.iz;
  }
  for (const Voxel& v : table) {
    if (!MayReachABand(v, Options())) continue;  // a leg's voxels below any band
    EXPECT_TRUE(Covered(out.prisms, v)) << v.ix << " " << v.iy << " " << v.iz;
  }
  // Floor columns with nothing on them and the steps (each 4 cm above the surfaces around
  // it, less than the band) are in no prism.
  for (int ix = 0; ix < 100; ++ix) {
    for (int iy = 0; iy < 50; ++iy) {
      const bool wall_column = ix >= 25 && ix <= 29 && iy <= 29;
      const bool table_column = ix >= 50 && ix <= 69 && iy >= 10 && iy <= 29;
      if (!wall_column && !table_column) {
        EXPECT_FALSE(AnyPrismOverColumn(out.prisms, ix, iy)) << ix << " " << iy;
      }
    }
  }
  // The table's top is a prism of its own above the floor: a body low enough walks under it.
  int table_tops = 0;
  BodyExtent low_body;
  low_body.min_m = Eigen::Vector2d(-0.1, -0.05);
  low_body.max_m = Eigen::Vector2d(0.1, 0.05);
  low_body.bottom_m = 0.10;
  low_body.top_m = 0.30;
  for (const MapPrism& p : out.prisms) {
    const double cx = 0.5 * (p.min_world_m.x() + p.max_world_m.x()), cy = 0.5 * (p.min_world_m.y() + p.max_world_m.y());
    BodyObstacle o;
    o.polygon_world_m = {p.min_world_m, {p.max_world_m.x(), p.min_world_m.y()}, p.max_world_m,
                         {p.min_world_m.x(), p.max_world_m.y()}};
    o.bottom_z_m = p.bottom_z_m;
    o.top_z_m = p.top_z_m;
    // The table's top: above the band of a body standing on the floor under it.
    if (cx > 1.0 && cx < 1.4 && cy > 0.2 && cy < 0.6 && p.bottom_z_m > 0.3) {
      EXPECT_FALSE(InBodyBand(low_body, o, 0.0));
      ++table_tops;
    }
  }
  EXPECT_GT(table_tops, 0);
  // Rectangles of equal columns: the floor-free wall is one prism, the table a handful.
  EXPECT_LE(out.prisms.size(), 12u);
}

// Random posts of random heights on a floor: every voxel whose top is above the floor's
// top by more than the band less a voxel lies in a prism; the floor alone is in none.
TEST(MapBodyObstacles, EveryVoxelAboveTheFloorBandIsInAPrismAmongRandomPosts) {
  std::mt19937 rng(29);
  std::uniform_int_distribution<int> at(0, 59), size(0, 4), height(0, 20);
  OccupancyMap map;
  map.resolution_m = kRes;
  AddBlock(&map, nullptr, 0, 59, 0, 59, -1, -1);
  std::vector<Voxel> posts;
  for (int k = 0; k < 40; ++k) {
    const int x = at(rng), y = at(rng), w = size(rng), h = height(rng);
    AddBlock(&map, &posts, x, std::min(59, x + w), y, std::min(59, y + w), 0, h);
  }
  const MapObstacleOptions options = Options();
  const MapObstacles out = MapBodyObstacles(map, options);
  ASSERT_TRUE(out.complete) << out.message;
  int above = 0;
  for (const Voxel& v : posts) {
    if (!MayReachABand(v, options)) continue;
    ++above;
    EXPECT_TRUE(Covered(out.prisms, v)) << v.ix << " " << v.iy << " " << v.iz;
  }
  EXPECT_GT(above, 100);
  EXPECT_LT(out.prisms.size(), 200u);
  // A column of floor alone: in no prism.
  std::vector<std::vector<bool>> post_column(60, std::vector<bool>(60, false));
  for (const Voxel& v : posts) post_column[v.ix][v.iy] = true;
  for (int ix = 0; ix < 60; ++ix) {
    for (int iy = 0; iy < 60; ++iy) {
      if (!post_column[ix][iy]) {
        EXPECT_FALSE(AnyPrismOverColumn(out.prisms, ix, iy));
      }
    }
  }
}

// A scanned wall and clutter: per column a random top and a floor with missing voxels.
// With bands on 0.1 m steps, every voxel that may reach a body's band lies in a prism,
// every prism's band is on the steps (or starts at the lowest level a band reaches), no
// column without such a voxel is under a prism, and there are far fewer prisms than with
// exact bands (a third fewer at least).
TEST(MapBodyObstacles, BandsOnStepsHoldEveryVoxelOfANoisyWallInFewerPrisms) {
  std::mt19937 rng(25);
  std::uniform_int_distribution<int> top(20, 27), coin(0, 9), at(0, 59), height(5, 15);
  OccupancyMap map;
  map.resolution_m = kRes;
  std::vector<Voxel> tall;
  for (int ix = 0; ix < 60; ++ix) {
    for (int iy = 0; iy < 60; ++iy) {
      if (coin(rng) > 0) AddBlock(&map, nullptr, ix, ix, iy, iy, -1, -1);  // a floor with holes
    }
  }
  for (int ix = 20; ix < 23; ++ix) {
    for (int iy = 0; iy < 60; ++iy) AddBlock(&map, &tall, ix, ix, iy, iy, coin(rng) > 7 ? 1 : 0, top(rng));
  }
  for (int k = 0; k < 30; ++k) {
    const int x = at(rng), y = at(rng);
    AddBlock(&map, &tall, x, x, y, y, 0, height(rng));
  }
  MapObstacleOptions exact = Options();
  exact.band_step_m = kRes;
  MapObstacleOptions stepped = Options();
  stepped.band_step_m = 0.1;
  const MapObstacles exact_out = MapBodyObstacles(map, exact);
  const MapObstacles out = MapBodyObstacles(map, stepped);
  ASSERT_TRUE(out.complete && exact_out.complete) << out.message << exact_out.message;
  int checked = 0;
  std::vector<std::vector<bool>> reaching(60, std::vector<bool>(60, false));
  for (const Voxel& v : tall) {
    if (!MayReachABand(v, stepped)) continue;
    ++checked;
    reaching[v.ix][v.iy] = true;
    EXPECT_TRUE(Covered(out.prisms, v)) << v.ix << " " << v.iy << " " << v.iz;
    EXPECT_TRUE(Covered(exact_out.prisms, v)) << v.ix << " " << v.iy << " " << v.iz;
  }
  EXPECT_GT(checked, 1000);
  for (int ix = 0; ix < 60; ++ix) {
    for (int iy = 0; iy < 60; ++iy) {
      if (!reaching[ix][iy]) {
        EXPECT_FALSE(AnyPrismOverColumn(out.prisms, ix, iy)) << ix << " " << iy;
      }
    }
  }
  const double step = stepped.band_step_m;
  for (const MapPrism& p : out.prisms) {
    EXPECT_NEAR(std::remainder(p.top_z_m, step), 0.0, 1e-9) << p.top_z_m;
    EXPECT_NEAR(std::remainder(p.bottom_z_m, step), 0.0, 1e-9) << p.bottom_z_m;
    EXPECT_GE(p.bottom_z_m, -kRes - 1e-9);  // nothing below the floor's voxels
  }
  EXPECT_LT(3 * out.prisms.size(), 2 * exact_out.prisms.size()) << out.prisms.size() << " vs " << exact_out.prisms.size();
}

TEST(MapBodyObstacles, ABudgetOrAnExpiredDeadlineGivesNoPrismsAndSaysWhy) {
  OccupancyMap map;
  map.resolution_m = kRes;
  AddBlock(&map, nullptr, 0, 9, 0, 9, 0, 9);
  MapObstacleOptions options = Options();
  options.max_leaf_columns = 50;
  MapObstacles out = MapBodyObstacles(map, options);
  EXPECT_FALSE(out.complete);
  EXPECT_TRUE(out.prisms.empty());
  EXPECT_NE(out.message.find("budget"), std::string::npos) << out.message;
  options = Options();
  options.deadline = Deadline::After(0.0);
  out = MapBodyObstacles(map, options);
  EXPECT_FALSE(out.complete);
  EXPECT_NE(out.message.find("time"), std::string::npos) << out.message;
}

}  // namespace
}  // namespace mfp
