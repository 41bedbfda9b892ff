// Issue 25 (walks on real scans): a goal's yaw is an angle, so a window turns the body
// by the shorter way to it. A goal across the +-pi seam from the stance (start 3.0 rad,
// goal -3.0 rad: 0.28 rad apart) must not make the windows turn the body 6 rad the
// long way round, and a stance whose yaw the windows have wound past pi must not be
// turned back through every heading to reach the goal's number.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

ConvexRegion Floor(int id, double x0, double y0, double x1, double y1) {
  return MakeRegionFromPolygon(id, {{x0, y0, 0.0}, {x1, y0, 0.0}, {x1, y1, 0.0}, {x0, y1, 0.0}}, 0.005);
}

class GoalYawSeamTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { course_ = new Course(LoadCourse("hexapod_flat.yaml")); }
  static void TearDownTestSuite() { delete course_; }

  // The hexapod standing at its nominal stance at (0, 0, start_yaw), asked to (0.4, 0, goal_yaw).
  PlanRequest Request(double start_yaw_rad, double goal_yaw_rad) const {
    const RobotModel& robot = course_->robot;
    PlanRequest r = course_->request;
    r.start_yaw_rad = start_yaw_rad;
    for (int leg = 0; leg < robot.num_legs(); ++leg) {
      const Eigen::Vector2d xy = NominalFootXY(robot, leg, 0.0, 0.0, start_yaw_rad);
      r.start_feet_world_m[leg] = Eigen::Vector3d(xy.x(), xy.y(), 0.0);
    }
    r.goal_x_m = 0.4;
    r.goal_y_m = 0.0;
    r.goal_yaw_rad = goal_yaw_rad;
    r.time_limit_s = 60.0;
    return r;
  }
  Plan PlanOn(const std::vector<ConvexRegion>& regions, const PlanRequest& request) const {
    const PlannerOptions& options = course_->scenario.options;
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
    return PlanFootsteps(course_->robot, regions, request, options, solvers.workers());
  }
  std::vector<std::string> Violations(const std::vector<ConvexRegion>& regions, const Plan& plan) const {
    const PlannerOptions& o = course_->scenario.options;
    return ValidatePlan(course_->robot, regions, plan,
                        {plan.goal_x_m, plan.goal_y_m, plan.goal_yaw_rad, o.goal_tolerance_m, o.goal_yaw_tolerance_rad},
                        ValidationTolerances{});
  }
  // The farthest any configuration's yaw turns from the start's, as numbers [rad].
  static double LargestTurn(const Plan& plan, double start_yaw_rad) {
    double turn = 0.0;
    for (const Footstep& f : plan.footsteps) turn = std::max(turn, std::abs(f.yaw_rad - start_yaw_rad));
    return turn;
  }
  static Course* course_;
};
Course* GoalYawSeamTest::course_ = nullptr;

TEST_F(GoalYawSeamTest, AGoalAcrossTheSeamIsReachedByTheShortTurn) {
  const std::vector<ConvexRegion> regions = {Floor(0, -1.5, -1.5, 2.0, 1.5)};
  for (const double start_yaw : {3.0, -3.0}) {
    const double goal_yaw = -start_yaw;
    const double short_turn = std::abs(std::remainder(goal_yaw - start_yaw, 2 * M_PI));
    ASSERT_LT(short_turn, 0.3);
    const PlanRequest request = Request(start_yaw, goal_yaw);
    const Plan plan = PlanOn(regions, request);
    ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
    EXPECT_TRUE(plan.reaches_goal) << plan.message;
    const std::vector<std::string> violations = Violations(regions, plan);
    EXPECT_TRUE(violations.empty()) << violations.front();
    // The body turns by the short way (0.28 rad, with the windows' slack about it), never
    // through the headings between: the long way is 6 rad.
    EXPECT_LT(LargestTurn(plan, start_yaw), short_turn + 0.5) << "start yaw " << start_yaw;
  }
}

// The windows compare the stance's yaw and the goal's as numbers: a stance wound past the
// seam (the windows' yaw is continuous) and a goal yaw given whole turns away are the same
// case. A goal given two turns away from a heading 0.2 rad left of the start's is that
// heading: the body turns 0.2 rad, not 4 pi + 0.2.
TEST_F(GoalYawSeamTest, AGoalYawWholeTurnsAwayIsTheSameHeading) {
  const std::vector<ConvexRegion> regions = {Floor(0, -1.5, -1.5, 2.0, 1.5)};
  const double start_yaw = 3.0, goal_yaw = 3.2 - 4 * M_PI;
  const PlanRequest request = Request(start_yaw, goal_yaw);
  const Plan plan = PlanOn(regions, request);
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  EXPECT_TRUE(plan.reaches_goal) << plan.message;
  const double short_turn = std::abs(std::remainder(goal_yaw - start_yaw, 2 * M_PI));
  EXPECT_LT(LargestTurn(plan, start_yaw), short_turn + 0.5);
}

}  // namespace
}  // namespace mfp
