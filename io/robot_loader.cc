#include "io/robot_loader.h"

#include <algorithm>
#include <cctype>

#include "base/check.h"
#include "io/robot_yaml.h"
#include "planner/robot/derivation_budget.h"
#include "planner/robot/urdf_reader.h"

namespace mfp {
namespace {

std::string LowerExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

RobotModel LoadRobot(const std::string& path) { return LoadRobot(path, nullptr); }

RobotModel LoadRobot(const std::string& path, RobotDerivation* derivation) {
  const std::string ext = LowerExtension(path);
  if (ext == ".urdf") {
    RobotDescription description = ReadUrdfRobot(path);
    const DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &description);
    RobotDerivation derived = DeriveRobot(description, options);
    ValidateRobotModel(derived.model);
    RobotModel model = derived.model;
    if (derivation != nullptr) *derivation = std::move(derived);
    return model;
  }
  if (ext == ".yaml" || ext == ".yml") return LoadRobotYaml(path, derivation);
  throw InputError(path + ": robot file must end in .urdf, .yaml or .yml");
}

}  // namespace mfp
