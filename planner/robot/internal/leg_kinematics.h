#pragma once
// Kinematic chains of legs as plain Eigen data: what the URDF adapter produces and what
// the robot derivation samples. One chain runs from the body (the URDF root link) to a
// foot; forward kinematics gives the foot point in the body frame.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mfp {

struct JointModel {
  enum class Type { kRevolute, kPrismatic, kFixed };
  std::string name;
  Type type = Type::kFixed;
  // Pose of the joint frame in the parent link frame at zero joint position (URDF origin).
  Eigen::Isometry3d T_parent_joint = Eigen::Isometry3d::Identity();
  // Unit axis in the joint frame (revolute: rotation axis, prismatic: direction).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  // Position limits [rad] or [m]; continuous joints are given [-pi, pi].
  double lower = 0.0;
  double upper = 0.0;

  bool movable() const { return type != Type::kFixed; }
};

struct LegChain {
  std::string name;       // stable leg name (see urdf_reader.h for the rule)
  std::string foot_link;  // the leaf link that carries the foot
  // Joints from the root link to the foot link, in order; fixed joints included.
  std::vector<JointModel> joints;
  // Foot point in the foot link frame [m]: a collision sphere's centre or the origin.
  Eigen::Vector3d p_footlink_foot_m = Eigen::Vector3d::Zero();
  // Radius of that collision sphere [m]; 0 when the foot is the link origin.
  double foot_sphere_radius_m = 0.0;

  int num_dof() const;
  // Limits of the movable joints, in chain order.
  Eigen::VectorXd LowerLimits() const;
  Eigen::VectorXd UpperLimits() const;
};

// The robot as a set of leg chains hanging from one body frame (the URDF root link).
struct RobotDescription {
  std::string name;
  std::string root_link;
  std::vector<LegChain> legs;
  std::string source;  // the file it was read from, for messages
  // What the reader chose or assumed (body link below a frame root, ignored links, joint
  // ranges given to continuous or placeholder limits, foot choices); shown as provenance.
  std::vector<std::string> notes;
  // The body link's extent in the body frame [m]: the bounding box of its collision
  // boxes, cylinders and spheres, else of its visual ones, else the box of uniform density
  // with its inertia; empty when the link has none of these (meshes are not read).
  Eigen::AlignedBox3d body_box_m;
  std::string body_box_source;  // which of those it was, for provenance
};

// Turns the body frame about z so that the robot's forward direction, at forward_yaw_rad
// from the URDF root's x axis, becomes x (every leg's first joint pose is rotated).
void TurnForwardToX(RobotDescription* robot, double forward_yaw_rad);

// Foot point in the body frame for movable-joint positions q (size num_dof()).
Eigen::Vector3d FootPosition(const LegChain& leg, const Eigen::VectorXd& q);

// Origins of the leg's movable joints (hip, knee, ...) in the body frame for joint
// positions q, in chain order [m].
std::vector<Eigen::Vector3d> MovableJointOrigins(const LegChain& leg, const Eigen::VectorXd& q);

// The leg's hip in the body frame, at zero joint positions: the point of the first
// movable joint's axis nearest the next movable joint's origin (or the foot); the first
// joint's origin when it is a slider.
Eigen::Vector3d HipPosition(const LegChain& leg);

// When every movable joint of the leg is revolute about one common axis (the foot moves
// in a plane, no sideways freedom): that axis in the body frame as text; else "".
std::string PlanarLegAxis(const LegChain& leg);

// Jacobian d(foot)/dq in the body frame, 3 x num_dof(), by central differences.
Eigen::MatrixXd FootJacobian(const LegChain& leg, const Eigen::VectorXd& q);

struct IkResult {
  bool converged = false;
  Eigen::VectorXd q;          // within the joint limits
  double error_m = 0.0;       // |FK(q) - target|
};

// Damped least-squares inverse kinematics for the foot point, joint positions clamped to
// their limits at every iteration, from the given start. Converged when the error is
// below tolerance_m.
IkResult SolveFootIk(const LegChain& leg, const Eigen::Vector3d& target_body_m,
                     const Eigen::VectorXd& q_start, double tolerance_m = 1e-5,
                     int max_iterations = 200);

}  // namespace mfp
