// Issue 27's hostile inputs, each run through the tool a user would run, as a child
// process: a clear error (exit 2, the message naming the problem) or a plan, with peak
// memory (the child's ru_maxrss) under 1 GiB, never a signal; wall times are recorded as
// test properties. The inputs: a tiny map whose leaves are 4096 voxels wide, URDFs that are not
// regular files (/dev/zero, a FIFO), every URDF number class at +-1e308, flag values out of range,
// a time limit that ends before any region is extracted.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "bench/hostile_inputs.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

const std::string kTools = std::string(MFP_BINARY_DIR) + "/tools/";
const std::string kSource = std::string(MFP_SOURCE_DIR) + "/";
constexpr double kMaxPeakBytes = 1024.0 * 1024.0 * 1024.0;

ChildRun Execute(const std::vector<std::string>& argv, double kill_after_s) {
  return ExecuteChild(argv, kill_after_s, TestTempPath("stderr.txt"));
}

// A clear refusal: exit 2, the message containing `says`, under 1 GiB, no signal (a tool
// still running at Execute's kill time ends by SIGKILL and fails here). The wall time is
// recorded, not asserted (speed targets live in benchmarks): it is in the test's XML.
void ExpectRefused(const ChildRun& run, const std::string& says) {
  EXPECT_EQ(run.signal, 0) << run.err;
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find(says), std::string::npos) << run.err;
  EXPECT_LT(run.peak_bytes, kMaxPeakBytes);
  static int runs = 0;
  ++runs;
  testing::Test::RecordProperty("wall_s_" + std::to_string(runs), std::to_string(run.wall_s));
  testing::Test::RecordProperty("peak_mib_" + std::to_string(runs),
                                std::to_string(run.peak_bytes / (1024.0 * 1024.0)));
}

// 68 bytes (the was 91): leaves 4096 voxels wide (bench/hostile_inputs.h).
std::string HugeLeafMap() {
  const std::string path = TestTempPath("huge_leaves.bt");
  WriteHugeLeafMap(path);
  return path;
}

TEST(HostileInputs, HugeLeafMapIsRefusedBeforeExpansion) {
  const std::string map = HugeLeafMap();
  ExpectRefused(Execute({kTools + "mfp-regions", map, "--time-limit", "2"}, 30), "max_leaf_columns");
  ExpectRefused(Execute({kTools + "mfp-plan", "--robot", kSource + "config/robots/hexapod.yaml", "--terrain",
                         map, "--start", "0,0,0", "--goal", "1,0,0", "--time-limit", "2", "--quiet"},
                        30),
                "max_leaf_columns");
}

TEST(HostileInputs, NonRegularFilesAreRefusedWithoutReading) {
  const std::string fifo = TestTempPath("robot.urdf");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string zero = TestTempPath("zero.urdf");  // a URDF name, /dev/zero behind it
  ASSERT_EQ(::symlink("/dev/zero", zero.c_str()), 0);
  ExpectRefused(Execute({kTools + "mfp-robot", zero}, 30), "character device");
  ::unlink(zero.c_str());
  ExpectRefused(Execute({kTools + "mfp-robot", fifo}, 30), "FIFO");
  const std::string fifo_map = TestTempPath("map.bt");
  ASSERT_EQ(::mkfifo(fifo_map.c_str(), 0600), 0);
  ExpectRefused(Execute({kTools + "mfp-regions", fifo_map}, 30), "FIFO");
  ExpectRefused(Execute({kTools + "mfp-regions", "/dev/zero"}, 30), "character device");
  ::unlink(fifo.c_str());
  ::unlink(fifo_map.c_str());
}

// sphere_quad.urdf with the first occurrence of `from` replaced by `to`.
std::string EditedUrdf(const std::string& from, const std::string& to) {
  const std::string path = TestTempPath("edited.urdf");
  EXPECT_TRUE(WriteEditedUrdf(kSource + "tests/data/robots/sphere_quad.urdf", from, to, path)) << from;
  return path;
}

TEST(HostileInputs, UrdfLengthAt1e308IsRefusedNamingTheElement) {
  // The foot sphere's collision origin (fl_tibia): bad_alloc in the footprint grid before.
  const std::string urdf = EditedUrdf("<origin xyz=\"0.12 0 -0.02\"", "<origin xyz=\"1e308 0 -0.02\"");
  const ChildRun run = Execute({kTools + "mfp-robot", urdf}, 60);
  ExpectRefused(run, "<origin> attribute 'xyz' = '1e308'");
}

TEST(HostileInputs, EveryExtremeUrdfNumberIsRefusedOrFinite) {
  // Each number of the bench's list: a clear refusal (exit 2) or a robot, never a signal
  // or a gigabyte.
  for (const UrdfNumberEdit& edit : ExtremeUrdfNumbers()) {
    const ChildRun run = Execute({kTools + "mfp-robot", EditedUrdf(edit.from, edit.to)}, 60);
    EXPECT_EQ(run.signal, 0) << edit.what << ": " << run.err;
    EXPECT_TRUE(run.exit_code == 0 || run.exit_code == 2) << edit.what << ": exit " << run.exit_code << " " << run.err;
    EXPECT_LT(run.peak_bytes, kMaxPeakBytes) << edit.what;
  }
}

TEST(HostileInputs, FlagValuesAreRangeCheckedLikeTheScenarioKeys) {
  for (const FlagCase& f : ExtremeFlags()) {
    ExpectRefused(Execute(ScenarioPlanArgs(kTools, kSource, f.start, f.goal, f.time_limit), 60), f.says);
  }
}

TEST(HostileInputs, TimeRunningOutBeforeExtractionIsATimeLimit) {
  // The map file is read and extracted within the time limit: 1 ms is spent before.
  const std::string map = TestTempPath("flat.bt");
  ASSERT_EQ(std::system((kTools + "mfp-terrain " + kSource + "config/scenarios/hexapod_flat.yaml --out " + map +
                         " > /dev/null 2>&1").c_str()),
            0);
  const std::vector<std::string> args = {kTools + "mfp-plan", "--robot", kSource + "config/robots/hexapod.yaml",
                                         "--terrain", map, "--start", "0,0,0", "--goal", "1,0,0",
                                         "--time-limit", "0.001"};
  const ChildRun run = Execute(args, 60);
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_EQ(run.err.find("no terrain regions"), std::string::npos) << run.err;
  EXPECT_LT(run.peak_bytes, kMaxPeakBytes);
}

}  // namespace
}  // namespace mfp
