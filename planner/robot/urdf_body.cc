#include "planner/robot/internal/urdf_body.h"

#include <urdf_model/model.h>

#include <string>
#include <utility>

#include "planner/robot/internal/urdf_xml_checks.h"

namespace mfp {
namespace {

// Axis-aligned bounds, in the link frame, of the box of half-sizes `half` [m] centred at
// `origin` and turned by its rotation.
Eigen::AlignedBox3d PlacedBox(const Eigen::Vector3d& half, const urdf::Pose& origin) {
  const Eigen::Isometry3d T = ToIsometry(origin);
  const Eigen::AlignedBox3d local(-half, half);
  Eigen::AlignedBox3d box;
  for (int corner = 0; corner < 8; ++corner) {
    box.extend(T * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  }
  return box;
}

// Bounding box, in the link frame, of one primitive shape placed at `origin` [m]; empty
// for meshes (not read).
Eigen::AlignedBox3d ShapeBox(const urdf::Geometry& geometry, const urdf::Pose& origin) {
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& d = static_cast<const urdf::Box&>(geometry).dim;
      half = 0.5 * Eigen::Vector3d(d.x, d.y, d.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(geometry);
      half = Eigen::Vector3d(c.radius, c.radius, 0.5 * c.length);
      break;
    }
    case urdf::Geometry::SPHERE:
      half = Eigen::Vector3d::Constant(static_cast<const urdf::Sphere&>(geometry).radius);
      break;
    default:
      return Eigen::AlignedBox3d();
  }
  return PlacedBox(half, origin);
}

// The box of uniform density whose principal moments are the link's inertia (a box of
// sides a, b, c has Ixx = m (b^2 + c^2) / 12, ...), about the inertial origin; empty when
// the link has no mass or the moments fit no box.
Eigen::AlignedBox3d InertiaBox(const urdf::Inertial& inertial) {
  const double m = inertial.mass;
  if (!(m > 0.0)) return Eigen::AlignedBox3d();
  const double ixx = inertial.ixx, iyy = inertial.iyy, izz = inertial.izz;
  const Eigen::Vector3d squared = 6.0 / m * Eigen::Vector3d(iyy + izz - ixx, ixx + izz - iyy, ixx + iyy - izz);
  if (!(squared.minCoeff() > 0.0)) return Eigen::AlignedBox3d();
  const Eigen::Vector3d half = 0.5 * squared.cwiseSqrt();
  return PlacedBox(half, inertial.origin);
}

// Bounds of the primitive shapes of a link's collision or visual elements [m, link frame];
// empty when it has none (meshes are not read).
template <typename Elements>
Eigen::AlignedBox3d BoundsOfShapes(const Elements& elements) {
  Eigen::AlignedBox3d box;
  for (const auto& element : elements) {
    if (element && element->geometry) box.extend(ShapeBox(*element->geometry, element->origin));
  }
  return box;
}

}  // namespace

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  T.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y,
                                  pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return T;
}

urdf::LinkConstSharedPtr BodyLink(const urdf::LinkConstSharedPtr& root, std::vector<std::string>* notes) {
  urdf::LinkConstSharedPtr body = root;
  for (int depth = 0; depth < kMaxLinks && body->child_joints.size() == 1; ++depth) {
    const urdf::JointSharedPtr& joint = body->child_joints.front();
    if (joint->type != urdf::Joint::FLOATING && joint->type != urdf::Joint::FIXED) break;
    if (body->child_links.size() != 1) break;
    notes->push_back("body: link '" + body->child_links.front()->name + "', below '" + body->name +
                     "' by the " + (joint->type == urdf::Joint::FLOATING ? "floating" : "fixed") +
                     " joint '" + joint->name + "'");
    body = body->child_links.front();
  }
  return body;
}

void ReadBodyBox(const urdf::Link& body, RobotDescription* robot) {
  // The first of these that is not empty, in this order of preference.
  const std::pair<Eigen::AlignedBox3d, std::string> candidates[] = {
      {BoundsOfShapes(body.collision_array), "collision shapes of link '" + body.name + "'"},
      {BoundsOfShapes(body.visual_array), "visual shapes of link '" + body.name + "'"},
      {body.inertial ? InertiaBox(*body.inertial) : Eigen::AlignedBox3d(),
       "box of uniform density with the inertia of link '" + body.name + "'"},
  };
  for (const auto& [box, source] : candidates) {
    if (box.isEmpty()) continue;
    robot->body_box_m = box;
    robot->body_box_source = source;
    return;
  }
}

}  // namespace mfp
