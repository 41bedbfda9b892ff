// mfp-hostile-bench: one row per hostile input of issue 27, each run through the tool a
// user would run as a child process: its exit code (or signal), wall time against the
// input's time limit, and peak memory (ru_maxrss). The inputs are made by
// bench/hostile_inputs.h, which the suite's hostile_inputs_test shares.
//
// usage: mfp-hostile-bench [--dir DIR] [--only TEXT]
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/hostile_inputs.h"
#include "io/cli_parse.h"

namespace {

const std::string kSource = MFP_SOURCE_DIR;
const std::string kTools = std::string(MFP_BINARY_DIR) + "/tools";

struct Row {
  std::string input;
  std::vector<std::string> argv;
  double limit_s = NAN;  // the time limit the command was given (NaN: none)
};

// The first line of a tool's stderr, shortened for the table.
std::string FirstLine(const std::string& err) {
  std::string line = err.substr(0, err.find('\n'));
  if (line.size() > 70) line = line.substr(0, 67) + "...";
  return line;
}

std::string Tool(const std::string& name) { return kTools + "/" + name; }

std::vector<Row> FileRows(const std::string& dir) {
  const std::string huge = dir + "/huge_leaves.bt", fifo_urdf = dir + "/robot_fifo.urdf",
                    zero_urdf = dir + "/zero.urdf", fifo_map = dir + "/map_fifo.bt";
  mfp::WriteHugeLeafMap(huge);
  ::unlink(fifo_urdf.c_str());
  ::unlink(fifo_map.c_str());
  ::unlink(zero_urdf.c_str());
  if (::mkfifo(fifo_urdf.c_str(), 0600) != 0 || ::mkfifo(fifo_map.c_str(), 0600) != 0 ||
      ::symlink("/dev/zero", zero_urdf.c_str()) != 0) {
    std::fprintf(stderr, "cannot make the FIFOs and the /dev/zero link in %s\n", dir.c_str());
    std::exit(1);
  }
  const std::string hexapod = kSource + "/config/robots/hexapod.yaml";
  return {
      {"huge-leaf .bt (68 B, 2^27 cells), mfp-regions", {Tool("mfp-regions"), huge, "--time-limit", "2"}, 2.0},
      {"huge-leaf .bt, mfp-plan",
       {Tool("mfp-plan"), "--robot", hexapod, "--terrain", huge, "--start", "0,0,0", "--goal", "1,0,0",
        "--time-limit", "2", "--quiet"},
       2.0},
      {"URDF -> /dev/zero, mfp-robot", {Tool("mfp-robot"), zero_urdf}, NAN},
      {"URDF a FIFO, mfp-robot", {Tool("mfp-robot"), fifo_urdf}, NAN},
      {"map a FIFO, mfp-regions", {Tool("mfp-regions"), fifo_map}, NAN},
      {"map /dev/zero, mfp-regions", {Tool("mfp-regions"), "/dev/zero"}, NAN},
  };
}

std::vector<Row> UrdfNumberRows(const std::string& dir) {
  std::vector<Row> rows;
  int k = 0;
  for (const mfp::UrdfNumberEdit& edit : mfp::ExtremeUrdfNumbers()) {
    const std::string path = dir + "/number_" + std::to_string(k++) + ".urdf";
    if (!mfp::WriteEditedUrdf(kSource + "/tests/data/robots/sphere_quad.urdf", edit.from, edit.to, path)) continue;
    rows.push_back({"URDF " + edit.what + ", mfp-robot", {Tool("mfp-robot"), path}, NAN});
  }
  return rows;
}

std::vector<Row> FlagRows() {
  std::vector<Row> rows;
  for (const mfp::FlagCase& f : mfp::ExtremeFlags()) {
    rows.push_back({"mfp-plan --start " + f.start + " --goal " + f.goal + " --time-limit " + f.time_limit,
                    mfp::ScenarioPlanArgs(kTools, kSource, f.start, f.goal, f.time_limit), NAN});
  }
  return rows;
}

// Inputs that are valid but large or short of time: a plan or a time limit, in time.
std::vector<Row> LoadRows(const std::string& dir) {
  const std::string flat = dir + "/flat.bt", sixteen = dir + "/sixteen_legs.urdf", stones = dir + "/stones_1000.yaml";
  const std::string hexapod = kSource + "/config/robots/hexapod.yaml";
  if (std::system((Tool("mfp-terrain") + " " + kSource + "/config/scenarios/hexapod_flat.yaml --out " + flat +
                   " > /dev/null 2>&1").c_str()) != 0 ||
      std::system(("python3 " + kSource + "/bench/many_stones.py 1000 " + stones + " --robot " + hexapod +
                   " > /dev/null").c_str()) != 0) {
    std::fprintf(stderr, "cannot write the flat map or the 1000-stone scenario in %s\n", dir.c_str());
    std::exit(1);
  }
  mfp::WriteSixteenLegUrdf(kSource + "/tests/data/robots/octopod.urdf", sixteen);
  return {
      {"16-leg URDF (the octopod's legs doubled), mfp-robot", {Tool("mfp-robot"), sixteen}, NAN},
      {"16-leg robot on a flat map, mfp-plan",
       {Tool("mfp-plan"), "--robot", sixteen, "--terrain", flat, "--start", "0,0,0", "--goal", "1,0,0",
        "--time-limit", "2", "--quiet"},
       2.0},
      {"1000-region scenario (many_stones.py 1000), mfp-plan",
       {Tool("mfp-plan"), "--scenario", stones, "--time-limit", "5", "--quiet"},
       5.0},
      {"--time-limit 0.001 on a flat map, mfp-plan",
       {Tool("mfp-plan"), "--robot", hexapod, "--terrain", flat, "--start", "0,0,0", "--goal", "1,0,0",
        "--time-limit", "0.001", "--quiet"},
       0.001},
  };
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Issue 27's hostile inputs through the tools: exit, wall time, peak memory"};
  std::string dir = "/tmp/mfp_hostile_bench";
  std::string only;
  app.add_option("--dir", dir, "folder for the generated inputs");
  app.add_option("--only", only, "rows whose input contains TEXT");
  MFP_CLI_PARSE(app, argc, argv);
  ::mkdir(dir.c_str(), 0755);
  std::vector<Row> rows = FileRows(dir);
  for (std::vector<Row> more : {UrdfNumberRows(dir), FlagRows(), LoadRows(dir)}) {
    rows.insert(rows.end(), more.begin(), more.end());
  }
  std::printf("%-66s %6s %7s %7s %8s  %s\n", "input", "exit", "wall_s", "limit_s", "peak_MiB", "first line of stderr");
  int over = 0;
  for (const Row& row : rows) {
    if (!only.empty() && row.input.find(only) == std::string::npos) continue;
    const mfp::ChildRun run = mfp::ExecuteChild(row.argv, 120.0, dir + "/stderr.txt");
    const std::string exit = run.signal != 0 ? "sig" + std::to_string(run.signal) : std::to_string(run.exit_code);
    const double peak_mib = run.peak_bytes / (1024.0 * 1024.0);
    const bool late = std::isfinite(row.limit_s) && run.wall_s > row.limit_s + 0.5;
    over += run.signal != 0 || late || peak_mib >= 1024.0 ? 1 : 0;
    std::printf("%-66s %6s %7.3f %7s %8.1f  %s\n", row.input.c_str(), exit.c_str(), run.wall_s,
                std::isfinite(row.limit_s) ? std::to_string(row.limit_s).substr(0, 5).c_str() : "-", peak_mib,
                FirstLine(run.err).c_str());
    std::fflush(stdout);
  }
  std::printf("rows past their limit + 0.5 s, at 1 GiB or more, or ended by a signal: %d\n", over);
  return over == 0 ? 0 : 1;
}
