// What a window's re-certification keeps of its plan (planner/planning/internal/goal_keeping.h):
// once the plan reaches the goal, its final feet stay within the goal's tolerance and the
// steps it takes stay taken. The ranges are boxes inside each foot's tolerance disc that
// hold the plan's foot, and the taken steps' trims at 0; a plan that does not reach the
// goal, or a window aiming at a local goal, keeps nothing.
#include "planner/planning/internal/goal_keeping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/robot_loader.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {
namespace {

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1) {
  return MakeRegionFromPolygon(id, {{x0, y0, 0.0}, {x1, y0, 0.0}, {x1, y1, 0.0}, {x0, y1, 0.0}}, 0.0);
}

class GoalKeepingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = LoadRobot(std::string(MFP_SOURCE_DIR) + "/config/robots/littledog.yaml");
    regions_.push_back(Rect(0, -0.5, -0.5, 1.0, 0.5));
    for (int leg = 0; leg < robot_.num_legs(); ++leg) {
      const Eigen::Vector2d xy = NominalFootXY(robot_, leg, 0.0, 0.0, 0.0);
      request_.start_feet_world_m.emplace_back(xy.x(), xy.y(), 0.0);
    }
    request_.goal_x_m = 0.2;
    goal_.x_m = request_.goal_x_m;
    goal_.tolerance_m = 0.05;
  }

  // A point of the window's MIQP whose final new feet stand `offset` from their goal
  // spots and whose last `trimmed` steps are trimmed (only those variables are read).
  Eigen::VectorXd FinalFeetAt(const MiqpFormulation& f, const Eigen::Vector2d& offset, int trimmed = 0) const {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(f.miqp().num_variables());
    for (int i = f.num_steps() - trimmed; i < f.num_steps(); ++i) x(f.vars().trim[i]) = 1.0;
    for (int i = f.num_steps() - f.num_legs(); i < f.num_steps(); ++i) {
      if (f.vars().x[i] < 0) continue;
      const Eigen::Vector2d at = f.GoalFoot(f.LegOfStep(i)) + offset;
      x(f.vars().x[i]) = at.x();
      x(f.vars().y[i]) = at.y();
    }
    return x;
  }

  RobotModel robot_;
  std::vector<ConvexRegion> regions_;
  PlanRequest request_;
  GoalSpec goal_;
  PlannerOptions options_;
};

// Every range pair is a box about the foot's goal spot, inside the tolerance's disc, that
// holds the plan's foot; near the spot the box is the disc's inscribed square.
TEST_F(GoalKeepingTest, ThePlansFinalFeetKeepBoxesInsideTheToleranceThatHoldThem) {
  const MiqpFormulation f(FirstWindowProblem(robot_, regions_, request_, options_), options_.formulation);
  ASSERT_GE(f.num_steps() - f.num_legs(), f.num_legs()) << "every final foot should be a new step";
  const double tol = goal_.tolerance_m;
  for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.01, -0.02),
                                       Eigen::Vector2d(0.045, 0.01), Eigen::Vector2d(-0.002, -0.049)}) {
    const Eigen::VectorXd x = FinalFeetAt(f, offset);
    const std::vector<VariableRange> ranges = GoalKeepingRanges(f, goal_, x);
    const size_t feet = static_cast<size_t>(2 * f.num_legs());
    ASSERT_EQ(ranges.size(), feet + static_cast<size_t>(f.num_steps() - f.num_legs())) << offset.transpose();
    for (size_t k = 0; k < feet; k += 2) {
      const VariableRange& rx = ranges[k];
      const VariableRange& ry = ranges[k + 1];
      EXPECT_LE(rx.lower, x(rx.index));
      EXPECT_GE(rx.upper, x(rx.index));
      EXPECT_LE(ry.lower, x(ry.index));
      EXPECT_GE(ry.upper, x(ry.index));
      const double half_x = 0.5 * (rx.upper - rx.lower), half_y = 0.5 * (ry.upper - ry.lower);
      EXPECT_LE(std::hypot(half_x, half_y), tol + 1e-12) << "a corner of the box lies beyond the tolerance";
      if (offset.cwiseAbs().maxCoeff() <= tol / std::sqrt(2.0)) {
        EXPECT_NEAR(half_x, tol / std::sqrt(2.0), 1e-12);
        EXPECT_NEAR(half_y, tol / std::sqrt(2.0), 1e-12);
      } else {
        EXPECT_NEAR(std::max(half_x, half_y), offset.cwiseAbs().maxCoeff(), 1e-12);  // the far axis: its offset
      }
    }
  }
}

// The steps the plan takes stay taken (their trims held at 0); its trimmed steps stay free.
TEST_F(GoalKeepingTest, TheStepsThePlanTakesStayTaken) {
  const MiqpFormulation f(FirstWindowProblem(robot_, regions_, request_, options_), options_.formulation);
  constexpr int kTrimmed = 3;
  const std::vector<VariableRange> ranges = GoalKeepingRanges(f, goal_, FinalFeetAt(f, Eigen::Vector2d(0.0, 0.0), kTrimmed));
  std::vector<int> held;
  for (const VariableRange& r : ranges) {
    for (int i = f.num_legs(); i < f.num_steps(); ++i) {
      if (r.index == f.vars().trim[i]) {
        EXPECT_EQ(r.lower, 0.0);
        EXPECT_EQ(r.upper, 0.0);
        held.push_back(i);
      }
    }
  }
  std::vector<int> taken;
  for (int i = f.num_legs(); i < f.num_steps() - kTrimmed; ++i) taken.push_back(i);
  EXPECT_EQ(held, taken);
}

// A plan with one foot beyond the tolerance keeps nothing (it does not reach the goal);
// nor does a window whose MIQP aims at a local goal along the route.
TEST_F(GoalKeepingTest, APlanShortOfTheGoalOrAWindowAimingElsewhereKeepsNothing) {
  const MiqpFormulation f(FirstWindowProblem(robot_, regions_, request_, options_), options_.formulation);
  Eigen::VectorXd x = FinalFeetAt(f, Eigen::Vector2d(0.0, 0.0));
  const int last = f.num_steps() - 1;
  x(f.vars().x[last]) -= 0.051;
  EXPECT_TRUE(GoalKeepingRanges(f, goal_, x).empty());
  EXPECT_TRUE(GoalKeeping(f, goal_) != nullptr);

  FootstepProblem local = FirstWindowProblem(robot_, regions_, request_, options_);
  local.goal_x_m = 0.1;  // a point of the route short of the goal
  const MiqpFormulation g(local, options_.formulation);
  EXPECT_TRUE(GoalKeeping(g, goal_) == nullptr);
  EXPECT_TRUE(GoalKeepingRanges(g, goal_, FinalFeetAt(g, Eigen::Vector2d(0.0, 0.0))).empty());
}

// A window of fewer new steps than legs: the final stance keeps start feet, which the
// ranges cannot move; they must reach the goal too for the plan to keep anything.
TEST_F(GoalKeepingTest, StartFeetInTheFinalStanceMustReachTheGoalToo) {
  FootstepProblem two = FirstWindowProblem(robot_, regions_, request_, options_);
  two.num_new_steps = 2;
  const MiqpFormulation far(two, options_.formulation);
  EXPECT_TRUE(GoalKeepingRanges(far, goal_, FinalFeetAt(far, Eigen::Vector2d(0.0, 0.0))).empty())
      << "the start feet stand 0.2 m from their goal spots";
  two.goal_x_m = 0.02;  // the start stance's spots within 2 cm
  GoalSpec near = goal_;
  near.x_m = two.goal_x_m;
  const MiqpFormulation close(two, options_.formulation);
  const std::vector<VariableRange> ranges = GoalKeepingRanges(close, near, FinalFeetAt(close, Eigen::Vector2d(0.0, 0.0)));
  EXPECT_EQ(ranges.size(), 6u);  // the two new feet's x and y, and their trims
}

}  // namespace
}  // namespace mfp
