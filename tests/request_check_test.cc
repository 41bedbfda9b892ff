// CheckPlanRequest: every rejection of a plan request, with the status it gives and a
// message naming the problem. The one place user input is checked before planning.
#include "planner/planning/request_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/test_scenarios.h"

namespace mfp {
namespace {

class RequestCheckTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { course_ = new Course(LoadCourse("hexapod_flat.yaml")); }
  static void TearDownTestSuite() { delete course_; }

  RequestCheck Check(const PlanRequest& request) const {
    return CheckPlanRequest(course_->robot, course_->regions, request, course_->scenario.options);
  }
  static Course* course_;
};
Course* RequestCheckTest::course_ = nullptr;

void ExpectRejected(const RequestCheck& check, SolveStatus status, const std::string& names) {
  EXPECT_FALSE(check.ok());
  EXPECT_EQ(check.status, status) << check.message;
  EXPECT_NE(check.message.find(names), std::string::npos) << check.message;
}

TEST_F(RequestCheckTest, TheScenariosRequestPasses) { EXPECT_TRUE(Check(course_->request).ok()); }

TEST_F(RequestCheckTest, NoRegionsIsNoMap) {
  const RequestCheck check =
      CheckPlanRequest(course_->robot, {}, course_->request, course_->scenario.options);
  ExpectRejected(check, SolveStatus::kNoMap, "no terrain regions");
}

TEST_F(RequestCheckTest, SizesAndNumbersAreInvalidRequests) {
  PlanRequest r = course_->request;
  r.start_feet_world_m.pop_back();
  ExpectRejected(Check(r), SolveStatus::kInvalidRequest, "legs");
  r = course_->request;
  r.start_feet_world_m[2].x() = std::nan("");
  ExpectRejected(Check(r), SolveStatus::kInvalidRequest, "leg 2");
  r = course_->request;
  r.goal_yaw_rad = INFINITY;
  ExpectRejected(Check(r), SolveStatus::kInvalidRequest, "finite");
  r = course_->request;
  r.max_steps = -1;
  ExpectRejected(Check(r), SolveStatus::kInvalidRequest, "max_steps");
  r = course_->request;
  r.window_steps = 1001;
  ExpectRejected(Check(r), SolveStatus::kInvalidRequest, "window");
}

TEST_F(RequestCheckTest, AFootOffEveryRegionIsAnInvalidStart) {
  PlanRequest r = course_->request;
  r.start_feet_world_m[1].z() += 0.5;  // far above the ground, beyond start_tolerance
  ExpectRejected(Check(r), SolveStatus::kInvalidStart, "leg 1");
}

TEST_F(RequestCheckTest, AGoalBeyondReachOfEveryRegionIsAnInvalidGoal) {
  PlanRequest r = course_->request;
  r.goal_x_m += 1000.0;
  ExpectRejected(Check(r), SolveStatus::kInvalidGoal, "nearest region");
}

TEST_F(RequestCheckTest, StepBudgetsFallBackToTheOptionsThenToMultiplesOfTheLegs) {
  const int n = course_->robot.num_legs();
  PlanRequest r = course_->request;
  PlannerOptions o;
  r.max_steps = 0;
  r.window_steps = 0;
  EXPECT_EQ(MaxSteps(course_->robot, r, o), 12 * n);
  EXPECT_EQ(WindowSteps(course_->robot, r, o), 2 * n);
  o.default_max_steps = 30;
  o.default_window_steps = 9;
  EXPECT_EQ(MaxSteps(course_->robot, r, o), 30);
  EXPECT_EQ(WindowSteps(course_->robot, r, o), 9);
  r.max_steps = 7;
  r.window_steps = 5;
  EXPECT_EQ(MaxSteps(course_->robot, r, o), 7);
  EXPECT_EQ(WindowSteps(course_->robot, r, o), 5);
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

// Issue 27: a degenerate stance, absurd yaws, and no regions because the time ran out.
TEST_F(RequestCheckTest, EveryStartFootAtOnePointIsAnInvalidStartNamingTheField) {
  PlanRequest request = course_->request;
  for (Eigen::Vector3d& f : request.start_feet_world_m) f = request.start_feet_world_m.front();
  ExpectRejected(Check(request), SolveStatus::kInvalidStart, "start_feet: all 6 start feet");
}

TEST_F(RequestCheckTest, YawsBeyondOneTurnAreInvalid) {
  PlanRequest request = course_->request;
  request.goal_yaw_rad = 1e16;
  ExpectRejected(Check(request), SolveStatus::kInvalidRequest, "goal yaw = 1e+16 rad");
  request.goal_yaw_rad = -2.0 * M_PI;  // one turn is still a heading
  EXPECT_TRUE(Check(request).ok()) << Check(request).message;
  request.start_yaw_rad = 7.0;
  ExpectRejected(Check(request), SolveStatus::kInvalidRequest, "start yaw = 7 rad");
}

TEST_F(RequestCheckTest, NoRegionsAfterTheDeadlineIsATimeLimit) {
  PlanRequest request = course_->request;
  request.deadline = Deadline::After(0.0);
  const RequestCheck check = CheckPlanRequest(course_->robot, {}, request, course_->scenario.options);
  ExpectRejected(check, SolveStatus::kTimeLimit, "time limit reached before planning");
}

}  // namespace
}  // namespace mfp
