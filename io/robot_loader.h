#pragma once
// One entry point for `--robot FILE`: a URDF alone (everything derived, defaults for
// what a URDF cannot say) or a robot YAML (robot_yaml.h), chosen by the extension.
#include <string>

#include "base/deadline.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// FILE.urdf or FILE.yaml / FILE.yml. The result passed ValidateRobotModel. A robot derived
// from a URDF gets each leg's footprint polygon, the 16-gon where none fits a leg
// (DerivationOptions' reach_shape), unless its YAML states another. Throws
// InputError (missing file, bad URDF or YAML, unknown extension, a leg that cannot stand).
RobotModel LoadRobot(const std::string& path);

// The same, also returning the derivation details when the robot comes from a URDF
// (`derivation->legs` is left empty for a hand-written YAML).
RobotModel LoadRobot(const std::string& path, RobotDerivation* derivation);

// The same, deriving a URDF robot by `deadline` (its stop flag too): throws TimeLimitError
// naming the stage once it expires.
RobotModel LoadRobot(const std::string& path, RobotDerivation* derivation, const Deadline& deadline);

// The same with the reach polygon given by the caller (mfp-terrain-bench --walk-reach): a
// robot from a URDF, alone or through a YAML, is derived for `reach_shape` whatever its
// YAML says; a hand-written YAML's d_lim becomes that polygon's half-width.
RobotModel LoadRobot(const std::string& path, ReachShape reach_shape);

}  // namespace mfp
