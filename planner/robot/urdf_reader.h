#pragma once
// Reads a URDF into leg chains (leg_kinematics.h). The only file that includes urdfdom
// and TinyXML2 headers. urdfdom accepts some broken input silently (NaN and infinite
// numbers, a zero joint axis, lower limit above upper); those are checked here.
//
// Body: the root link, or below a root that is only a frame (one floating or fixed joint
// to the next link, as `world` or a `base` above `trunk`). Links in no joint are ignored;
// joints that form a loop are refused.
// Legs: chains from the body with at least two movable joints ending at a foot, or the
// chains to the links named in `foot_links` when it is not empty. Feet: among the leaf
// links below a leg's first movable joint, leaves hanging by fixed joints partway along
// the leg (rotors, covers) are dropped, then one is kept preferring a collision sphere,
// a foot/toe/tip name, more movable joints, the point farthest from the hip. Leaves that
// hang off the body by fixed joints only (sensors, cameras) are not legs. Foot point: the
// centre of the foot link's first collision sphere, else the link origin, or
// `foot_offset_m` in the foot link when given. A leg whose foot point sits on its last
// joint's axis is refused (the URDF holds no foot). Leg order: the order of the legs'
// first movable joints in the file. Leg name: the longest common prefix of the
// chain's link names with trailing '_' or '-' removed ("front_left_hip",
// "front_left_upper_leg", ... -> "front_left"), else the longest common suffix
// ("abduct_fr", "thigh_fr", ... -> "fr"), else the foot link's name.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "planner/robot/internal/leg_kinematics.h"

namespace mfp {

// Throws InputError naming the file (and line, element, attribute where known) when the
// file is missing, unreadable or malformed, has no legs, or has invalid joints.
// Limits: 10,000 links, 16 legs, 12 movable joints per leg, 64 joints from body to foot.
RobotDescription ReadUrdfRobot(const std::string& path,
                               const std::vector<std::string>& foot_links = {},
                               const std::optional<Eigen::Vector3d>& foot_offset_m = std::nullopt);

}  // namespace mfp
