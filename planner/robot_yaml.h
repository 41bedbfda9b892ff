#pragma once
// Loads config/robots/NAME.yaml into a RobotModel. The YAML holds what a URDF cannot
// say (gait, stance height, foot radius, weights) and, until a URDF is given, the legs'
// nominal offsets and reach limits. Every value read is recorded in provenance.
#include <string>

#include "planner/robot_model.h"

namespace mfp {

// Throws InputError naming the file, key and allowed range on bad input.
RobotModel LoadRobotYaml(const std::string& path);

}  // namespace mfp
