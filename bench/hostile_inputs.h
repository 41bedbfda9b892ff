#pragma once
// Issue 27's hostile inputs, shared by the suite (tests/hostile_inputs_test.cc asserts
// each class's outcome) and the bench (mfp-hostile-bench prints a row per input): the
// files that make them, the tool command lines that feed them, and a child-process runner
// that records the exit, the wall time and the peak memory.
#include <string>
#include <vector>

namespace mfp {

struct ChildRun {
  int exit_code = -1;  // -1 when the child did not exit normally
  int signal = 0;      // the signal that ended it (0: none)
  double wall_s = 0.0;
  double peak_bytes = 0.0;  // the child's ru_maxrss
  std::string err;          // its stderr
};

// Runs argv[0] (an executable path) with argv, stdout to /dev/null and stderr to
// stderr_path; SIGKILLs it at kill_after_s (reported through signal = SIGKILL) so a
// hanging tool ends.
ChildRun ExecuteChild(const std::vector<std::string>& argv, double kill_after_s, const std::string& stderr_path);

// A .bt map at 0.1 m, 68 bytes, whose only branch ends in 8 occupied leaves 4096 voxels
// (410 m) wide, 2^27 column cells in all: every header and count check passes.
void WriteHugeLeafMap(const std::string& path);

// source_urdf with the first occurrence of `from` replaced by `to`, written to path.
// False when `from` does not occur (nothing written).
bool WriteEditedUrdf(const std::string& source_urdf, const std::string& from, const std::string& to,
                     const std::string& path);

// One number of sphere_quad.urdf set to an extreme value: the edit and what it names.
struct UrdfNumberEdit {
  std::string what;  // for a table row: "collision origin x = 1e308"
  std::string from, to;
};
std::vector<UrdfNumberEdit> ExtremeUrdfNumbers();

// octopod_urdf with each leg copied once, 3 cm lower, under new names: 16 legs of the
// octopod's joints. Throws std::runtime_error when the file cannot be read.
void WriteSixteenLegUrdf(const std::string& octopod_urdf, const std::string& path);

// mfp-plan on the little dog's flat scenario with these --start, --goal and --time-limit.
std::vector<std::string> ScenarioPlanArgs(const std::string& tools_dir, const std::string& source_dir,
                                          const std::string& start, const std::string& goal,
                                          const std::string& time_limit);

// Flag values that mfp-plan must refuse (exit 2), each with the text the refusal holds.
struct FlagCase {
  std::string start, goal, time_limit;
  std::string says;
};
std::vector<FlagCase> ExtremeFlags();

}  // namespace mfp
