#include "io/robot_loader.h"

#include <optional>

#include "base/check.h"
#include "io/file_paths.h"
#include "io/robot_yaml.h"
#include "planner/robot/derivation_budget.h"
#include "planner/robot/urdf_reader.h"

namespace mfp {

RobotModel LoadRobot(const std::string& path) { return LoadRobot(path, nullptr); }

RobotModel LoadRobot(const std::string& path, RobotDerivation* derivation) {
  return LoadRobot(path, derivation, Deadline());
}

namespace {

RobotModel LoadRobotShaped(const std::string& path, RobotDerivation* derivation, const Deadline& deadline,
                           std::optional<ReachShape> reach_shape) {
  const std::string ext = LowerFileExtension(path);
  if (ext == "urdf") {
    RobotDescription description = ReadUrdfRobot(path);
    DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &description);
    if (reach_shape) {
      options.reach_shape = *reach_shape;
      options.reach_shape_given = "by the caller";
    }
    options.deadline = deadline;
    RobotDerivation derived = DeriveRobot(description, options);
    ValidateRobotModel(derived.model);
    RobotModel model = derived.model;
    if (derivation != nullptr) *derivation = std::move(derived);
    return model;
  }
  if (ext == "yaml" || ext == "yml") return LoadRobotYaml(path, derivation, deadline, reach_shape);
  throw InputError(path + ": robot file must end in .urdf, .yaml or .yml");
}

}  // namespace

RobotModel LoadRobot(const std::string& path, RobotDerivation* derivation, const Deadline& deadline) {
  return LoadRobotShaped(path, derivation, deadline, std::nullopt);
}

RobotModel LoadRobot(const std::string& path, ReachShape reach_shape) {
  return LoadRobotShaped(path, nullptr, Deadline(), reach_shape);
}

}  // namespace mfp
