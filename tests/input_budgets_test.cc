// Issue 27's budgets and messages, unit by unit: the bounded regular-file reader, the
// leaf-column cap of maps (stream and memory), the map format field, names escaped in
// published messages, the flag values of mfp-plan, and the derivation work budget.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "base/bounded_file.h"
#include "base/check.h"
#include "base/format.h"
#include "daemon/map_regions.h"
#include "daemon/message_conversion.h"
#include "io/cli_values.h"
#include "planner/robot/derivation_budget.h"
#include "planner/robot/urdf_reader.h"
#include "terrain/extraction/internal/surface_layers.h"
#include "terrain/extraction/leaf_budget.h"
#include "terrain/octomap/octomap_io.h"
#include "tests/input_error_of.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

std::string Source(const std::string& rel) { return std::string(MFP_SOURCE_DIR) + "/" + rel; }

std::string ErrorOf(const std::function<void()>& f) { return InputErrorOf(f); }

TEST(BoundedFile, ReadsARegularFileAndRefusesEverythingElse) {
  const std::string file = TestTempPath("small.txt");
  std::ofstream(file) << "hello";
  EXPECT_EQ(ReadBoundedRegularFile(file, 5, "test file"), "hello");
  EXPECT_NE(ErrorOf([&] { ReadBoundedRegularFile(file, 4, "test file"); }).find("more than the limit of 4 bytes"),
            std::string::npos);
  const std::string fifo = TestTempPath("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(ErrorOf([&] { ReadBoundedRegularFile(fifo, 100, "URDF"); }).find("is a FIFO (named pipe)"),
            std::string::npos);
  ::unlink(fifo.c_str());
  EXPECT_NE(ErrorOf([&] { ReadBoundedRegularFile("/dev/zero", 100, "URDF"); }).find("character device"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadBoundedRegularFile("/tmp", 100, "URDF"); }).find("a directory"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadBoundedRegularFile("/nonexistent/x", 100, "URDF"); }).find("no such file"),
            std::string::npos);
}

// Occupied leaves `n` voxels wide stacked in one column, at 0.1 m.
OccupancyMap StackedLeaves(int count, int n) {
  OccupancyMap map;
  map.resolution_m = 0.1;
  for (int k = 0; k < count; ++k) {
    const double size = 0.1 * n;
    map.leaves.push_back({Eigen::Vector3d(0.5 * size, 0.5 * size, (k + 0.5) * size), size});
  }
  return map;
}

TEST(LeafBudget, CountsEachLeafsFootprintNotItsNodes) {
  EXPECT_EQ(LeafColumnCells(StackedLeaves(3, 4)), 48u);
  OccupancyMap map = StackedLeaves(1, 4);
  // A free leaf counts only inside the occupied extent (4 x 4 of its 16 x 16 columns).
  map.free_leaves.push_back({Eigen::Vector3d(0.8, 0.8, 3.0), 1.6});
  EXPECT_EQ(LeafColumnCells(map), 16u + 16u);
  const std::string error = ErrorOf([] { CheckLeafColumnBudget(StackedLeaves(8, 4096), kDefaultMaxLeafColumns); });
  EXPECT_NE(error.find("SurfaceLayerOptions::max_leaf_columns"), std::string::npos) << error;
  EXPECT_NE(error.find("134217728"), std::string::npos) << error;
}

// The layers check the same budget with the same error, before expanding the leaves
// into columns: the occupied leaves' part first, the free leaves' part summed by their
// footprints' pass (free space asked) or by the budget's own (not asked).
TEST(LeafBudget, TheLayersRefuseTheMapOverTheBudgetWithItsWholeCount) {
  OccupancyMap map = StackedLeaves(1, 4);  // 16 column cells
  map.free_leaves.push_back({Eigen::Vector3d(0.8, 0.8, 0.8), 1.6});  // 16 of its 256 inside the extent
  map.free_leaves.push_back({Eigen::Vector3d(0.2, 0.2, 9.0), 0.4});  // 16, far above any surface
  ASSERT_EQ(LeafColumnCells(map), 48u);
  for (const bool seen_from_above : {true, false}) {
    for (const int threads : {1, 2, 3}) {
      SurfaceLayerOptions options;
      options.require_seen_from_above = seen_from_above;
      options.threads = threads;
      options.max_leaf_columns = 48;
      EXPECT_NO_THROW(BuildSurfaceLayers(map, options));
      options.max_leaf_columns = 47;
      const std::string error = ErrorOf([&] { BuildSurfaceLayers(map, options); });
      EXPECT_NE(error.find("cover 48 x-y column cells"), std::string::npos) << error;
      EXPECT_NE(error.find("SurfaceLayerOptions::max_leaf_columns"), std::string::npos) << error;
      options.max_leaf_columns = 15;  // the occupied part alone is over
      EXPECT_NE(ErrorOf([&] { BuildSurfaceLayers(map, options); }).find("cover 48 x-y"), std::string::npos);
    }
  }
  // A map whose leaves the grid refuses (over max_cells) and over the budget names the
  // budget, as when the budget was checked first.
  SurfaceLayerOptions options;
  options.max_cells = 4;
  options.max_leaf_columns = 47;
  EXPECT_NE(ErrorOf([&] { BuildSurfaceLayers(map, options); }).find("max_leaf_columns"), std::string::npos);
  options.max_leaf_columns = 48;
  EXPECT_NE(ErrorOf([&] { BuildSurfaceLayers(map, options); }).find("height map limit"), std::string::npos);
}

// A .bt like the 91-byte one (68 bytes): 8 occupied leaves 4096 voxels wide
// under one branch.
std::vector<uint8_t> HugeLeafBytes() {
  const std::string header = "# Octomap OcTree binary file\nid OcTree\nsize 12\nres 0.1\ndata\n";
  std::vector<uint8_t> bytes(header.begin(), header.end());
  for (uint8_t b : {0x03, 0x00, 0x03, 0x00, 0x03, 0x00, 0xAA, 0xAA}) bytes.push_back(b);
  return bytes;
}

TEST(LeafBudget, TheStreamCheckRefusesHugeLeavesBeforeOctoMapReadsThem) {
  const std::vector<uint8_t> bytes = HugeLeafBytes();
  const std::string error = ErrorOf([&] { LoadMapBytes(bytes, "map message"); });
  EXPECT_NE(error.find("map message: not a usable map"), std::string::npos) << error;
  EXPECT_NE(error.find("4096 voxels wide"), std::string::npos) << error;
  EXPECT_NE(error.find("OctreeStreamLimits::max_leaf_columns"), std::string::npos) << error;
  // Raised, the same tree reads (its cost is the caller's choice then).
  OctreeStreamLimits raised;
  raised.max_leaf_columns = uint64_t{1} << 28;
  EXPECT_EQ(LoadMapBytes(bytes, "map message", raised).leaves.size(), 8u);
}

TEST(MapFormat, AnUnknownFormatIsRefusedNamingIt) {
  const MapFunction regions = MakeOctomapMapFunction(DaemonSetup{});
  const std::vector<uint8_t> map = OccupancyMapBytes(StackedLeaves(1, 1), true);
  const std::string bytes(map.begin(), map.end());
  EXPECT_NO_THROW(regions(bytes, "", "m"));
  EXPECT_NO_THROW(regions(bytes, "bt", "m"));
  EXPECT_NE(ErrorOf([&] { regions(bytes, "png", "m"); }).find("format 'png' is not a map format"),
            std::string::npos);
}

TEST(EscapedNames, ControlBytesCannotForgeALineOrCutAString) {
  EXPECT_EQ(EscapedText(std::string("a\nb\0c\x1b\t", 7)), "a\\nb\\0c\\x1b\\t");
  EXPECT_EQ(EscapedText("hexapod \xc3\xa9"), "hexapod \xc3\xa9");  // UTF-8 stays
  const plan_t reply = StatusReply(SolveStatus::kInvalidRequest, "robot: unknown robot 'x\nINFO forged'", 7,
                                   "x\nINFO forged", 0, 0);
  EXPECT_EQ(reply.robot, "x\\nINFO forged");
  EXPECT_EQ(reply.message.find('\n'), std::string::npos);
  const region_set_t set = ToRegionSetMessage({}, std::string("wor\0ld", 6), 0, 0);
  EXPECT_EQ(set.frame, "wor\\0ld");
  std::vector<uint8_t> buffer(static_cast<size_t>(set.getEncodedSize()));
  EXPECT_EQ(set.encode(buffer.data(), 0, static_cast<int>(buffer.size())), static_cast<int>(buffer.size()));
}

TEST(CliValues, PosesAndNumbersAreCheckedLikeTheYamlKeys) {
  EXPECT_EQ(PoseFlagProblem("0,0,0", "--start"), "");
  EXPECT_EQ(PoseFlagProblem("-1.5,2e3,3.1", "--goal"), "");
  EXPECT_NE(PoseFlagProblem("0,0,0,", "--start").find("4 fields"), std::string::npos);
  EXPECT_NE(PoseFlagProblem("0,,0", "--start").find("Y = '' is not a number"), std::string::npos);
  EXPECT_NE(PoseFlagProblem("0,0,1e16", "--start").find("YAW = 1e16 is outside"), std::string::npos);
  EXPECT_NE(PoseFlagProblem("1e10,0,0", "--goal").find("X = 1e10 is outside"), std::string::npos);
  EXPECT_NE(PoseFlagProblem("0,nan,0", "--goal").find("Y = nan is outside"), std::string::npos);
  EXPECT_NE(PoseFlagProblem("0,0, 1", "--goal").find("not a number"), std::string::npos);
  EXPECT_EQ(NumberFlagProblem("2.5", "--time-limit", 1e-3, 3600), "");
  EXPECT_NE(NumberFlagProblem("nan", "--time-limit", 1e-3, 3600).find("not a finite number"), std::string::npos);
  EXPECT_NE(NumberFlagProblem("inf", "--time-limit", 1e-3, 3600).find("not a finite number"), std::string::npos);
  EXPECT_NE(NumberFlagProblem("5s", "--time-limit", 1e-3, 3600).find("is not a number"), std::string::npos);
}

TEST(DerivationBudget, RobotsOfTheRepositoryKeepTheDefaultGrids) {
  for (const char* urdf : {"tests/data/robots/octopod.urdf", "config/robots/littledog.urdf",
                           "tests/data/robots/sphere_quad.urdf"}) {
    RobotDescription robot = ReadUrdfRobot(Source(urdf));
    const DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &robot);
    EXPECT_LE(DerivationWork(robot, DerivationOptions{}), kMaxDerivationWork) << urdf;
    EXPECT_EQ(options.final_cells, DerivationOptions{}.final_cells) << urdf;
    EXPECT_EQ(options.stance_candidates, DerivationOptions{}.stance_candidates) << urdf;
  }
}

TEST(DerivationBudget, SixteenLegsOfTwelveJointsAreDerivedOnCoarserGridsAndSaySo) {
  RobotDescription robot = ReadUrdfRobot(Source("tests/data/robots/octopod.urdf"));
  robot.legs.resize(2);
  for (LegChain& leg : robot.legs) {
    const LegChain one = leg;
    for (int k = 1; k < 4; ++k) leg.joints.insert(leg.joints.end(), one.joints.begin(), one.joints.end());
  }
  robot.legs.resize(16, robot.legs.front());
  ASSERT_EQ(robot.legs.front().num_dof(), 12);
  const DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &robot);
  EXPECT_LE(DerivationWork(robot, options), 1.2 * kMaxDerivationWork);
  EXPECT_LT(options.final_cells, DerivationOptions{}.final_cells);
  ASSERT_FALSE(robot.notes.empty());
  EXPECT_NE(robot.notes.back().find("derivation budget: 16 legs"), std::string::npos) << robot.notes.back();
}

}  // namespace
}  // namespace mfp
