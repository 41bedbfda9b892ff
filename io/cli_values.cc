#include "io/cli_values.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "base/format.h"

namespace mfp {
namespace {

// The number `field` is, whole (no trailing text, no blanks), or false.
bool WholeNumber(const std::string& field, double* value) {
  if (field.empty() || std::isspace(static_cast<unsigned char>(field.front()))) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(field.c_str(), &end);
  return end == field.c_str() + field.size();
}

std::string Quoted(const std::string& text) { return "'" + EscapedText(text.substr(0, 64)) + "'"; }

// "FLAG: " (nothing when CLI11 names the flag itself, flag "").
std::string Prefix(const std::string& flag) { return flag.empty() ? "" : flag + ": "; }

}  // namespace

std::string PoseFlagProblem(const std::string& text, const std::string& flag) {
  const char* kNames[3] = {"X", "Y", "YAW"};
  std::vector<std::string> fields(1);
  for (const char ch : text) {
    if (ch == ',') {
      fields.emplace_back();
    } else {
      fields.back().push_back(ch);
    }
  }
  if (fields.size() != 3) {
    return Prefix(flag) + "expected X,Y,YAW (three numbers: m, m, rad), got " + Quoted(text) + " (" +
           std::to_string(fields.size()) + " fields)";
  }
  for (size_t i = 0; i < 3; ++i) {
    double v = 0.0;
    if (!WholeNumber(fields[i], &v)) {
      return Prefix(flag) + kNames[i] + " = " + Quoted(fields[i]) + " is not a number (expected X,Y,YAW in m, m, rad)";
    }
    const double limit = i < 2 ? kMaxPoseCoordinateM : kMaxPoseYawRad;
    if (!std::isfinite(v) || std::abs(v) > limit) {
      return Prefix(flag) + kNames[i] + " = " + fields[i] + " is outside [-" + Number(limit) + ", " +
             Number(limit) + "] " + (i < 2 ? "m" : "rad (one turn either way)");
    }
  }
  return "";
}

std::string NumberFlagProblem(const std::string& text, const std::string& flag, double min,
                              double max) {
  double v = 0.0;
  if (!WholeNumber(text, &v)) return Prefix(flag) + Quoted(text) + " is not a number";
  if (!std::isfinite(v) || v < min || v > max) {
    return Prefix(flag) + text + " is not a finite number in [" + Number(min) + ", " + Number(max) + "]";
  }
  return "";
}

// CLI11 puts the flag's name before a validator's message: the messages leave it out.
CLI::Validator PoseFlag() {
  return CLI::Validator([](std::string& text) { return PoseFlagProblem(text, ""); }, "X,Y,YAW");
}

CLI::Validator FiniteRange(double min, double max) {
  std::ostringstream description;
  description << "finite number in [" << min << ", " << max << "]";
  return CLI::Validator(
      [min, max](std::string& text) { return NumberFlagProblem(text, "", min, max); },
      description.str());
}

}  // namespace mfp
