// FlatSeenDisk (geometry/seen_surface.h), the flatness test of goal and start footholds on
// seen floor: two voxel levels inside its disk are sensor noise when the cells of the scarcer
// level are scattered (one-voxel pits and bumps), and a riser or curb when they form a run
// across the disk; a foothold stands on the former, never on the latter.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "geometry/seen_surface.h"

namespace mfp {
namespace {

constexpr double kCell = 0.05;    // a 5 cm map, as fr_079
constexpr double kRadius = 0.12;  // the disk asked for: about 2.4 cells (plus one cell of edge uncertainty)

// Floor at height 0 over [0, 1] x [0, 1], 5 cm cells.
SurfaceGrid Floor() {
  SurfaceGrid g;
  g.resolution_m = kCell;
  g.rows = 20;
  g.cols = 20;
  g.height_m.assign(static_cast<size_t>(g.rows * g.cols), 0.0f);
  return g;
}

void Raise(SurfaceGrid* g, int col, int row) {
  g->height_m[static_cast<size_t>(row * g->cols + col)] = static_cast<float>(kCell);
}

std::optional<SeenDisk> DiskAtCentre(const SurfaceGrid& g) {
  SeenSurface s;
  s.grids.push_back(g);
  return FlatSeenDisk(s, Eigen::Vector2d(0.5, 0.5), kRadius);  // the corner of cells (9, 9) and (10, 10)
}

TEST(FlatSeenDiskTest, FlatFloorIsFlat) {
  const std::optional<SeenDisk> disk = DiskAtCentre(Floor());
  ASSERT_TRUE(disk.has_value());
  EXPECT_DOUBLE_EQ(disk->low_m, 0.0);
  EXPECT_DOUBLE_EQ(disk->high_m, 0.0);
}

TEST(FlatSeenDiskTest, ScatteredOneVoxelBumpsAndPitsAreNoise) {
  SurfaceGrid g = Floor();
  // Three isolated bumps and a pair, one voxel up, inside the disk.
  Raise(&g, 8, 8);
  Raise(&g, 11, 9);
  Raise(&g, 9, 11);
  Raise(&g, 11, 11);
  Raise(&g, 11, 12);
  const std::optional<SeenDisk> disk = DiskAtCentre(g);
  ASSERT_TRUE(disk.has_value());
  EXPECT_NEAR(disk->high_m - disk->low_m, kCell, 1e-6);
  // One-voxel pits in a floor one voxel up: the same.
  SurfaceGrid pits = Floor();
  for (float& h : pits.height_m) h = static_cast<float>(kCell);
  pits.height_m[static_cast<size_t>(10 * pits.cols + 10)] = 0.0f;
  pits.height_m[static_cast<size_t>(8 * pits.cols + 11)] = 0.0f;
  EXPECT_TRUE(DiskAtCentre(pits).has_value());
}

TEST(FlatSeenDiskTest, AOneVoxelCurbAcrossTheDiskIsNotFlat) {
  SurfaceGrid g = Floor();
  for (int row = 0; row < g.rows; ++row) Raise(&g, 10, row);  // a curb one cell wide along y at x = [0.5, 0.55)
  EXPECT_FALSE(DiskAtCentre(g).has_value());
}

TEST(FlatSeenDiskTest, AOneVoxelRiserThroughTheDiskIsNotFlat) {
  SurfaceGrid g = Floor();
  for (int row = 0; row < g.rows; ++row) {
    for (int col = 11; col < g.cols; ++col) Raise(&g, col, row);  // the floor steps up one voxel at x = 0.55
  }
  EXPECT_FALSE(DiskAtCentre(g).has_value());
}

}  // namespace
}  // namespace mfp
