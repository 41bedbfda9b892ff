// Issue 27's hostile inputs, each run through the tool a user would run, as a child
// process: a clear error (exit 2, the message naming the problem) or a plan, with peak
// memory (the child's ru_maxrss) under 1 GiB, never a signal; wall times are recorded as
// test properties. The inputs: a tiny map whose leaves are 4096 voxels wide, URDFs that are not
// regular files (/dev/zero, a FIFO), a URDF length at 1e308, flag values out of range,
// a time limit that ends before any region is extracted.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_temp_path.h"

namespace mfp {
namespace {

const std::string kTools = std::string(MFP_BINARY_DIR) + "/tools/";
const std::string kSource = std::string(MFP_SOURCE_DIR) + "/";
constexpr double kMaxPeakBytes = 1024.0 * 1024.0 * 1024.0;

struct ChildRun {
  int exit_code = -1;   // -1 when the child did not exit normally
  int signal = 0;       // the signal that ended it (0: none)
  double wall_s = 0.0;
  double peak_bytes = 0.0;
  std::string err;
};

// Runs `argv` with stderr to a file; kills it (and says so through signal = SIGKILL) at
// kill_after_s so a hanging tool fails the test instead of blocking it.
ChildRun Execute(const std::vector<std::string>& argv, double kill_after_s) {
  const std::string err_path = TestTempPath("stderr.txt");
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (!std::freopen(err_path.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout)) _exit(127);
    ::execv(args[0], args.data());
    _exit(127);
  }
  ChildRun run;
  int status = 0;
  struct rusage usage {};
  for (;;) {
    const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > kill_after_s) ::kill(pid, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  std::ifstream in(err_path);
  run.err.assign(std::istreambuf_iterator<char>(in), {});
  return run;
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

// 68 bytes (the was 91): a .bt tree at 0.1 m whose only branch ends in 8 occupied leaves 4096 voxels
// (410 m) wide, 2^27 column cells in all. Every header and count check passes.
std::string HugeLeafMap() {
  std::string bytes = "# Octomap OcTree binary file\nid OcTree\nsize 12\nres 0.1\ndata\n";
  const unsigned char tree[] = {0x03, 0x00, 0x03, 0x00, 0x03, 0x00, 0xAA, 0xAA};
  bytes.append(reinterpret_cast<const char*>(tree), sizeof(tree));
  const std::string path = TestTempPath("huge_leaves.bt");
  std::ofstream(path, std::ios::binary) << bytes;
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
  std::ifstream in(kSource + "tests/data/robots/sphere_quad.urdf");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const std::string path = TestTempPath("edited.urdf");
  std::ofstream(path) << text;
  return path;
}

TEST(HostileInputs, UrdfLengthAt1e308IsRefusedNamingTheElement) {
  // The foot sphere's collision origin (fl_tibia): bad_alloc in the footprint grid before.
  const std::string urdf = EditedUrdf("<origin xyz=\"0.12 0 -0.02\"", "<origin xyz=\"1e308 0 -0.02\"");
  const ChildRun run = Execute({kTools + "mfp-robot", urdf}, 60);
  ExpectRefused(run, "<origin> attribute 'xyz' = '1e308'");
}

std::vector<std::string> PlanArgs(const std::string& start, const std::string& goal,
                                  const std::string& time_limit) {
  return {kTools + "mfp-plan", "--scenario", kSource + "config/scenarios/littledog_flat.yaml", "--start",
          start, "--goal", goal, "--time-limit", time_limit, "--quiet"};
}

TEST(HostileInputs, FlagValuesAreRangeCheckedLikeTheScenarioKeys) {
  ExpectRefused(Execute(PlanArgs("0,0,1e16", "0.6,0,0", "5"), 60), "--start: YAW = 1e16 is outside");
  ExpectRefused(Execute(PlanArgs("1e16,0,0", "0.6,0,0", "5"), 60), "--start: X = 1e16 is outside");
  ExpectRefused(Execute(PlanArgs("0,0,0,", "0.6,0,0", "5"), 60), "--start: expected X,Y,YAW");
  ExpectRefused(Execute(PlanArgs("0,0,0", "0.6,0,1e16", "5"), 60), "--goal: YAW = 1e16 is outside");
  ExpectRefused(Execute(PlanArgs("0,0,0", "0.6,0,0", "nan"), 60), "--time-limit");
  ExpectRefused(Execute(PlanArgs("0,0,0", "0.6,0,0", "inf"), 60), "--time-limit");
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
