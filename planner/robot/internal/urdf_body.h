#pragma once
// The body of a URDF robot: which link the legs hang from and its extent. Private to the
// robot library: it names urdfdom types, so only urdf_reader.cc and urdf_body.cc include it.
#include <Eigen/Geometry>
#include <urdf_model/link.h>
#include <urdf_model/pose.h>

#include <string>
#include <vector>

#include "planner/robot/urdf_reader.h"

namespace mfp {

// The rigid transform a URDF origin states (translation [m], unit quaternion).
Eigen::Isometry3d ToIsometry(const urdf::Pose& pose);

// Below a root that is only a frame (`world`, `base` with a floating or fixed joint to the
// body and nothing else) lies the body the legs hang from; each frame skipped adds a note.
urdf::LinkConstSharedPtr BodyLink(const urdf::LinkConstSharedPtr& root, std::vector<std::string>* notes);

// Sets RobotDescription::body_box_m [m, body frame] and body_box_source from the body
// link's collision shapes, else its visual shapes, else the box of its inertia; leaves
// them unset when the link has none of these (meshes are not read).
void ReadBodyBox(const urdf::Link& body, RobotDescription* robot);

}  // namespace mfp
