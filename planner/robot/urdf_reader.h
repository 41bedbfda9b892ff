#pragma once
// Reads a URDF into leg chains (leg_kinematics.h). The only file that includes urdfdom
// and TinyXML2 headers. urdfdom accepts some broken input silently (NaN and infinite
// numbers, a zero joint axis, lower limit above upper); those are checked here.
//
// Legs: the chains from the root link to the leaf links that contain a movable joint, or
// to the links named in `foot_links` when it is not empty. Foot point: the centre of the
// foot link's first collision sphere, else the link origin. Leg order: the order of the
// legs' first movable joints in the file. Leg name: the longest common prefix of the
// chain's link names with trailing '_' or '-' removed ("front_left_hip",
// "front_left_upper_leg", ... -> "front_left"), else the foot link's name.
#include <string>
#include <vector>

#include "planner/robot/leg_kinematics.h"

namespace mfp {

// Throws InputError naming the file (and line, element, attribute where known) when the
// file is missing, unreadable or malformed, has no legs, or has invalid joints.
RobotDescription ReadUrdfRobot(const std::string& path,
                               const std::vector<std::string>& foot_links = {});

}  // namespace mfp
