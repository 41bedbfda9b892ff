// The real-scan walks' draw (bench/scan_walks.h): the default seed keeps the draw the
// measurements recorded, another seed draws other walks, and one seed draws the same
// walks every time.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scan_walks.h"
#include "io/robot_loader.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {
namespace {

constexpr double kRes = 0.1;  // voxel edge [m]

// A flat floor of 7 m x 7 m seen from above: one occupied voxel per column, known free
// space 1.2 m above it.
OccupancyMap FlatFloor() {
  OccupancyMap map;
  map.resolution_m = kRes;
  for (int i = 0; i < 70; ++i) {
    for (int j = 0; j < 70; ++j) {
      const double x = (i + 0.5) * kRes, y = (j + 0.5) * kRes;
      map.leaves.push_back({{x, y, 0.5 * kRes}, kRes});
      for (int k = 1; k <= 12; ++k) map.free_leaves.push_back({{x, y, (k + 0.5) * kRes}, kRes});
    }
  }
  return map;
}

const std::string kHexapod = std::string(MFP_SOURCE_DIR) + "/config/robots/hexapod.yaml";

ScanWalkOptions ThreeWalks() {
  ScanWalkOptions o;
  o.walks = 3;
  o.certifiable_ends = true;
  return o;
}

bool SameEnds(const std::vector<std::pair<Pose2D, Pose2D>>& a, const std::vector<std::pair<Pose2D, Pose2D>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    for (const auto& [p, q] : {std::make_pair(a[i].first, b[i].first), std::make_pair(a[i].second, b[i].second)}) {
      if (p.x_m != q.x_m || p.y_m != q.y_m || p.yaw_rad != q.yaw_rad) return false;
    }
  }
  return true;
}

TEST(ScanWalkSeedTest, DefaultSeedIsTheRecordedDraw) {
  EXPECT_EQ(ScanWalkOptions{}.seed, 25u);
  // The per-scan-and-robot seed of the recorded walks: 25 mixed with the
  // libstdc++ hash of the scan's file name and the robot's name.
  EXPECT_EQ(WalkDrawSeed(25, "/tmp/scans_data/geb079.bt", "anymal"), 1377961389u);
  EXPECT_EQ(WalkDrawSeed(25, "fr_079.bt", "hexapod"), 3934916487u);
}

TEST(ScanWalkSeedTest, SeedIgnoresTheScansDirectoryButNotItsNameOrTheRobot) {
  EXPECT_EQ(WalkDrawSeed(7, "/a/b/geb079.bt", "go1"), WalkDrawSeed(7, "geb079.bt", "go1"));
  EXPECT_NE(WalkDrawSeed(7, "geb079.bt", "go1"), WalkDrawSeed(7, "fr_079.bt", "go1"));
  EXPECT_NE(WalkDrawSeed(7, "geb079.bt", "go1"), WalkDrawSeed(7, "geb079.bt", "anymal"));
  EXPECT_NE(WalkDrawSeed(7, "geb079.bt", "go1"), WalkDrawSeed(8, "geb079.bt", "go1"));
}

TEST(ScanWalkSeedTest, OneSeedDrawsTheSameWalksAndAnotherSeedOthers) {
  const OccupancyMap map = FlatFloor();
  ScanWalkOptions o = ThreeWalks();
  const auto first = DrawWalkEnds(map, "flat.bt", kHexapod, o);
  ASSERT_EQ(first.size(), 3u);
  for (const auto& [start, goal] : first) {
    const double dx = goal.x_m - start.x_m, dy = goal.y_m - start.y_m;
    EXPECT_GE(dx * dx + dy * dy, o.min_length_m * o.min_length_m);
  }
  EXPECT_TRUE(SameEnds(first, DrawWalkEnds(map, "flat.bt", kHexapod, o)));
  o.seed = 26;
  const auto other = DrawWalkEnds(map, "flat.bt", kHexapod, o);
  ASSERT_EQ(other.size(), 3u);
  EXPECT_FALSE(SameEnds(first, other));
}

// Floor of 10 m x 10 m at 20 cm voxels (new_college's), one voxel higher from x = 5 m on:
// a change of level taller than the hexapod's dz_max (0.093 m).
constexpr double kCoarse = 0.2;
int LevelAt(double x_m) { return x_m >= 5.0 ? 1 : 0; }
OccupancyMap TwoLevelFloor() {
  OccupancyMap map;
  map.resolution_m = kCoarse;
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 50; ++j) {
      const double x = (i + 0.5) * kCoarse, y = (j + 0.5) * kCoarse;
      const int top = LevelAt(x);
      for (int k = 0; k <= top; ++k) map.leaves.push_back({{x, y, (k + 0.5) * kCoarse}, kCoarse});
      for (int k = top + 1; k <= top + 8; ++k) map.free_leaves.push_back({{x, y, (k + 0.5) * kCoarse}, kCoarse});
    }
  }
  return map;
}

TEST(ScanWalkLegsJoined, AFootThatMustChangeLevelByMoreThanDzMaxIsNotJoined) {
  const OccupancyMap map = TwoLevelFloor();
  const Pose2D straddling{5.0, 3.0, 0.0}, lower{2.0, 3.0, 0.0}, straddling_too{5.0, 7.0, 0.0};
  // Legs on the upper level at the start would have to step down a voxel to the goal.
  EXPECT_GE(LegNotJoinedAtItsHeight(map, kHexapod, straddling, lower), 0);
  // Every leg keeps its level: within the lower level, or straddling at both ends.
  EXPECT_EQ(LegNotJoinedAtItsHeight(map, kHexapod, lower, Pose2D{2.0, 7.0, 0.0}), -1);
  EXPECT_EQ(LegNotJoinedAtItsHeight(map, kHexapod, straddling, straddling_too), -1);
}

TEST(ScanWalkLegsJoined, TheLegsJoinedDrawKeepsEveryFootOnItsLevel) {
  const OccupancyMap map = TwoLevelFloor();
  ScanWalkOptions o = ThreeWalks();
  o.walks = 8;
  o.joined_ends = true;
  o.legs_joined_ends = true;
  const RobotModel robot = LoadRobot(kHexapod);
  const auto ends = DrawWalkEnds(map, "two_levels.bt", kHexapod, o);
  ASSERT_GE(ends.size(), 8u);
  for (size_t w = 0; w < 8; ++w) {  // the joined walks come first
    const auto& [start, goal] = ends[w];
    for (int leg = 0; leg < robot.num_legs(); ++leg) {
      const Eigen::Vector2d a = NominalFootXY(robot, leg, start.x_m, start.y_m, start.yaw_rad);
      const Eigen::Vector2d b = NominalFootXY(robot, leg, goal.x_m, goal.y_m, goal.yaw_rad);
      EXPECT_EQ(LevelAt(a.x()), LevelAt(b.x())) << "walk " << w << " leg " << leg;
    }
  }
}

}  // namespace
}  // namespace mfp
