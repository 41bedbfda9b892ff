#pragma once
// Values of command-line flags, checked as strictly as the YAML keys they stand for
// (io/yaml_fields.h): whole numbers of text, finite, in range. Each check is a
// plain function (for tests) and a CLI11 validator (for add_option(...)->check(...)), so
// a bad value is refused while the flags are parsed: exit 2 with the flag named.
#include <CLI/CLI.hpp>

#include <cmath>
#include <string>

namespace mfp {

// Largest |x|, |y| of a pose flag [m]: the range of the scenario keys start and goal.
constexpr double kMaxPoseCoordinateM = 1e9;
// Largest |yaw| of a pose flag [rad]: one turn either way. A heading is an angle; a yaw
// of 1e16 is a mistake, not a request to spin (CheckPlanRequest refuses it likewise).
constexpr double kMaxPoseYawRad = 2.0 * M_PI;

// "" when `text` is X,Y,YAW: exactly three comma-separated finite numbers (no empty
// field, so no trailing comma), |X|, |Y| <= kMaxPoseCoordinateM and |YAW| <=
// kMaxPoseYawRad; else the problem, naming the field, after "FLAG: " unless flag is "".
std::string PoseFlagProblem(const std::string& text, const std::string& flag);

// "" when `text` is one finite number in [min, max] (NaN and inf refused); else the
// problem, naming `flag`.
std::string NumberFlagProblem(const std::string& text, const std::string& flag, double min,
                              double max);

// The validators of add_option(...)->check(...); CLI11 names the flag in their messages.
CLI::Validator PoseFlag();
CLI::Validator FiniteRange(double min, double max);

}  // namespace mfp
