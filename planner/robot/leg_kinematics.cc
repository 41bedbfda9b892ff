#include "planner/robot/internal/leg_kinematics.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "base/check.h"

namespace mfp {
namespace {

Eigen::Isometry3d JointMotion(const JointModel& joint, double q) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  if (joint.type == JointModel::Type::kRevolute) {
    motion.linear() = Eigen::AngleAxisd(q, joint.axis).toRotationMatrix();
  } else if (joint.type == JointModel::Type::kPrismatic) {
    motion.translation() = q * joint.axis;
  }
  return motion;
}

// Walks the chain; calls visit(joint, T_body_joint, dof index or -1) for every joint and
// returns the pose of the foot link in the body frame.
template <typename Visit>
Eigen::Isometry3d WalkChain(const LegChain& leg, const Eigen::VectorXd& q, Visit visit) {
  MFP_CHECK(q.size() == leg.num_dof());
  Eigen::Isometry3d T_body_link = Eigen::Isometry3d::Identity();
  int dof = 0;
  for (const JointModel& joint : leg.joints) {
    const Eigen::Isometry3d T_body_joint = T_body_link * joint.T_parent_joint;
    visit(joint, T_body_joint, joint.movable() ? dof : -1);
    const double qi = joint.movable() ? q[dof++] : 0.0;
    T_body_link = T_body_joint * JointMotion(joint, qi);
  }
  return T_body_link;
}

// One field of each movable joint, in chain order.
Eigen::VectorXd MovableJointValues(const LegChain& leg, double JointModel::*field) {
  Eigen::VectorXd values(leg.num_dof());
  int dof = 0;
  for (const JointModel& joint : leg.joints) {
    if (joint.movable()) values[dof++] = joint.*field;
  }
  return values;
}

}  // namespace

int LegChain::num_dof() const {
  int n = 0;
  for (const JointModel& joint : joints) n += joint.movable() ? 1 : 0;
  return n;
}

Eigen::VectorXd LegChain::LowerLimits() const { return MovableJointValues(*this, &JointModel::lower); }

Eigen::VectorXd LegChain::UpperLimits() const { return MovableJointValues(*this, &JointModel::upper); }

void TurnForwardToX(RobotDescription* robot, double forward_yaw_rad) {
  const Eigen::Isometry3d turn(Eigen::AngleAxisd(-forward_yaw_rad, Eigen::Vector3d::UnitZ()));
  for (LegChain& leg : robot->legs) {
    if (!leg.joints.empty()) leg.joints.front().T_parent_joint = turn * leg.joints.front().T_parent_joint;
  }
  if (robot->body_box_m.isEmpty()) return;
  Eigen::AlignedBox3d turned;
  for (int corner = 0; corner < 8; ++corner) {
    turned.extend(turn * robot->body_box_m.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  }
  robot->body_box_m = turned;
}

Eigen::Vector3d FootPosition(const LegChain& leg, const Eigen::VectorXd& q) {
  const Eigen::Isometry3d T_body_foot =
      WalkChain(leg, q, [](const JointModel&, const Eigen::Isometry3d&, int) {});
  return T_body_foot * leg.p_footlink_foot_m;
}

std::vector<Eigen::Vector3d> MovableJointOrigins(const LegChain& leg, const Eigen::VectorXd& q) {
  std::vector<Eigen::Vector3d> origins;
  WalkChain(leg, q, [&](const JointModel& joint, const Eigen::Isometry3d& T, int) {
    if (joint.movable()) origins.push_back(T.translation());
  });
  return origins;
}

Eigen::Vector3d HipPosition(const LegChain& leg) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(leg.num_dof());
  // The first movable joint's axis (a line) and the origin of the next movable joint, or
  // the foot: the hip is the point of that line nearest it. A joint origin anywhere on
  // the axis describes the same leg, and some URDFs copy it from another leg.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::Zero();
  Eigen::Vector3d next = Eigen::Vector3d::Zero();
  int seen = 0;
  WalkChain(leg, zero, [&](const JointModel& joint, const Eigen::Isometry3d& T, int) {
    if (!joint.movable()) return;
    if (seen == 0) {
      origin = T.translation();
      if (joint.type == JointModel::Type::kRevolute) axis = T.linear() * joint.axis;
    } else if (seen == 1) {
      next = T.translation();
    }
    ++seen;
  });
  if (seen == 0) return origin;
  if (seen == 1) next = FootPosition(leg, zero);
  if (axis.squaredNorm() == 0.0) return origin;
  return origin + (next - origin).dot(axis) * axis;
}

std::string PlanarLegAxis(const LegChain& leg) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(leg.num_dof());
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  bool planar = true;
  WalkChain(leg, zero, [&](const JointModel& joint, const Eigen::Isometry3d& T, int) {
    if (!joint.movable()) return;
    const Eigen::Vector3d axis = T.linear() * joint.axis;
    if (joint.type != JointModel::Type::kRevolute) {
      planar = false;  // a slider moves the foot out of any one plane but along its axis
    } else if (first.squaredNorm() == 0.0) {
      first = axis;
    } else if (first.cross(axis).norm() > 1e-6) {
      planar = false;
    }
  });
  if (!planar || first.squaredNorm() == 0.0) return "";
  std::ostringstream text;
  text.precision(3);
  text << "(" << first.x() << ", " << first.y() << ", " << first.z() << ")";
  return text.str();
}

Eigen::MatrixXd FootJacobian(const LegChain& leg, const Eigen::VectorXd& q) {
  const Eigen::Vector3d foot = FootPosition(leg, q);
  Eigen::MatrixXd jacobian(3, leg.num_dof());
  WalkChain(leg, q, [&](const JointModel& joint, const Eigen::Isometry3d& T, int dof) {
    if (dof < 0) return;
    const Eigen::Vector3d axis_body = T.linear() * joint.axis;
    if (joint.type == JointModel::Type::kRevolute) {
      jacobian.col(dof) = axis_body.cross(foot - T.translation());
    } else {
      jacobian.col(dof) = axis_body;
    }
  });
  return jacobian;
}

IkResult SolveFootIk(const LegChain& leg, const Eigen::Vector3d& target_body_m,
                     const Eigen::VectorXd& q_start, double tolerance_m, int max_iterations) {
  const Eigen::VectorXd lower = leg.LowerLimits();
  const Eigen::VectorXd upper = leg.UpperLimits();
  IkResult result;
  result.q = q_start.cwiseMax(lower).cwiseMin(upper);
  // Damping keeps steps bounded near singular poses (straight knee); small enough that
  // convergence away from them is quadratic-like.
  const double damping_sq = 1e-6;
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::Vector3d error = target_body_m - FootPosition(leg, result.q);
    result.error_m = error.norm();
    if (result.error_m < tolerance_m) {
      result.converged = true;
      return result;
    }
    const Eigen::MatrixXd J = FootJacobian(leg, result.q);
    const Eigen::Matrix3d JJt = J * J.transpose() + damping_sq * Eigen::Matrix3d::Identity();
    const Eigen::VectorXd step = J.transpose() * JJt.ldlt().solve(error);
    result.q = (result.q + step).cwiseMax(lower).cwiseMin(upper);
  }
  result.error_m = (target_body_m - FootPosition(leg, result.q)).norm();
  result.converged = result.error_m < tolerance_m;
  return result;
}

}  // namespace mfp
