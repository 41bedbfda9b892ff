// Forward kinematics against hand-computed positions, the analytic Jacobian against
// finite differences, inverse kinematics within limits.
#include <gtest/gtest.h>

#include <cmath>

#include "planner/robot/internal/leg_kinematics.h"

namespace mfp {
namespace {

JointModel Revolute(const std::string& name, const Eigen::Vector3d& origin,
                    const Eigen::Vector3d& axis, double lower, double upper) {
  JointModel j;
  j.name = name;
  j.type = JointModel::Type::kRevolute;
  j.T_parent_joint.translation() = origin;
  j.axis = axis;
  j.lower = lower;
  j.upper = upper;
  return j;
}

// LittleDog's front-left leg: hip roll (x) at (0.101, 0.03625, 0), hip pitch (y) 0.0236 m
// further out, knee (y) 0.0751 m below, foot (-0.0265, 0, -0.0985) in the lower leg.
LegChain FrontLeftLeg() {
  LegChain leg;
  leg.name = "front_left";
  leg.joints = {Revolute("roll", {0.101, 0.03625, 0}, Eigen::Vector3d::UnitX(), -0.6, 0.6),
                Revolute("pitch", {0, 0.0236, 0}, Eigen::Vector3d::UnitY(), -3.5, 2.4),
                Revolute("knee", {0, 0, -0.0751}, Eigen::Vector3d::UnitY(), -3.1, 1.0)};
  leg.p_footlink_foot_m = Eigen::Vector3d(-0.0265, 0, -0.0985);
  return leg;
}

TEST(LegKinematics, ForwardKinematicsMatchesHandComputedPositions) {
  const LegChain leg = FrontLeftLeg();
  ASSERT_EQ(leg.num_dof(), 3);
  // Zero pose: offsets add up.
  const Eigen::Vector3d zero = FootPosition(leg, Eigen::Vector3d::Zero());
  EXPECT_NEAR(zero.x(), 0.101 - 0.0265, 1e-12);
  EXPECT_NEAR(zero.y(), 0.03625 + 0.0236, 1e-12);
  EXPECT_NEAR(zero.z(), -0.0751 - 0.0985, 1e-12);
  // Knee at +pi/2 about y maps the lower-leg point (x, 0, z) to (z, 0, -x).
  const Eigen::Vector3d knee = FootPosition(leg, Eigen::Vector3d(0, 0, M_PI / 2));
  EXPECT_NEAR(knee.x(), 0.101 - 0.0985, 1e-12);
  EXPECT_NEAR(knee.y(), 0.05985, 1e-12);
  EXPECT_NEAR(knee.z(), -0.0751 + 0.0265, 1e-12);
  // Hip roll +0.3 about x turns the hip-to-foot vector (0, 0.0236, -0.1736) in the y-z plane.
  const double r = 0.3;
  const Eigen::Vector3d roll = FootPosition(leg, Eigen::Vector3d(r, 0, 0));
  EXPECT_NEAR(roll.y(), 0.03625 + 0.0236 * std::cos(r) + 0.1736 * std::sin(r), 1e-12);
  EXPECT_NEAR(roll.z(), 0.0236 * std::sin(r) - 0.1736 * std::cos(r), 1e-12);
  EXPECT_TRUE(HipPosition(leg).isApprox(Eigen::Vector3d(0.101, 0.03625, 0)));
}

TEST(LegKinematics, JacobianMatchesFiniteDifferences) {
  const LegChain leg = FrontLeftLeg();
  const Eigen::Vector3d q(0.2, -0.7, 1.1);
  const Eigen::MatrixXd J = FootJacobian(leg, q);
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d dq = Eigen::Vector3d::Zero();
    dq[i] = 1e-6;
    const Eigen::Vector3d fd = (FootPosition(leg, q + dq) - FootPosition(leg, q - dq)) / 2e-6;
    EXPECT_LT((fd - J.col(i)).norm(), 1e-8) << "joint " << i;
  }
}

TEST(LegKinematics, InverseKinematicsReachesForwardKinematicsTargetsWithinLimits) {
  const LegChain leg = FrontLeftLeg();
  const Eigen::Vector3d targets_q[] = {{0.3, -0.5, 1.0}, {-0.4, 0.8, -1.2}, {0.1, -1.5, 0.5}};
  for (const Eigen::Vector3d& q_true : targets_q) {
    const Eigen::Vector3d target = FootPosition(leg, q_true);
    const IkResult ik = SolveFootIk(leg, target, q_true + Eigen::Vector3d(0.1, -0.1, 0.1));
    ASSERT_TRUE(ik.converged) << ik.error_m;
    EXPECT_LT((FootPosition(leg, ik.q) - target).norm(), 1e-5);
    EXPECT_TRUE((ik.q.array() >= leg.LowerLimits().array()).all());
    EXPECT_TRUE((ik.q.array() <= leg.UpperLimits().array()).all());
  }
  // Out of reach (0.19 m is the longest leg): no convergence, still within limits.
  const IkResult far = SolveFootIk(leg, Eigen::Vector3d(0.101, 0.06, -0.5), Eigen::Vector3d::Zero());
  EXPECT_FALSE(far.converged);
  EXPECT_TRUE((far.q.array() <= leg.UpperLimits().array()).all());
}

}  // namespace
}  // namespace mfp
