// The receding horizon's retries, stalls and longer looks (planner/planning/internal/
// horizon_policy.h) on the state they back up (horizon_state.h), with a hexapod's plan
// context on a flat field: the windows' steps are stand-ins appended to the state.
#include "planner/planning/internal/horizon_policy.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/planning/internal/plan_progress.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

class HorizonPolicyTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { course_ = new Course(LoadCourse("hexapod_flat.yaml")); }
  static void TearDownTestSuite() { delete course_; }

  // A guided context whose longest look is max_horizon_windows default windows.
  void SetUpContext(int max_horizon_windows) {
    options_ = course_->scenario.options;
    options_.max_horizon_windows = max_horizon_windows;
    request_ = course_->request;
    request_.max_steps = 200;
    context_ = std::make_unique<PlanContext>(course_->robot, course_->regions, request_, options_, solvers_);
    ASSERT_FALSE(SetUpPlan(context_.get()).has_value());
    ASSERT_TRUE(context_->guided);
    state_ = std::make_unique<HorizonState>(*context_);
  }
  int n() const { return course_->robot.num_legs(); }

  // A window that keeps `steps` footsteps, each foot moved by dx_m from where it stood.
  void KeepSteps(int steps, double dx_m) {
    Plan& plan = state_->plan;
    for (int k = 0; k < steps; ++k) {
      Footstep f = plan.footsteps[plan.footsteps.size() - static_cast<size_t>(n())];
      f.position_world_m.x() += dx_m;
      f.index = static_cast<int>(plan.footsteps.size());
      plan.footsteps.push_back(f);
    }
    state_->planned += steps;
  }
  // A window starts (the state's snapshot) and keeps one step per leg, each 0.1 m ahead.
  void KeepAWindow() {
    state_->TakeSnapshot();
    KeepSteps(n(), 0.1);
  }

  static Course* course_;
  PlannerOptions options_;
  PlanRequest request_;
  std::vector<RelaxationSolver*> solvers_;
  std::unique_ptr<PlanContext> context_;
  std::unique_ptr<HorizonState> state_;
};
Course* HorizonPolicyTest::course_ = nullptr;

TEST_F(HorizonPolicyTest, ANewFailureBacksUpPastTheWindowBeforeWithTwiceTheHorizon) {
  SetUpContext(2);
  HorizonPolicy policy(*context_);
  const int window = context_->window_steps;
  EXPECT_EQ(policy.NextWindowSteps(*state_), window);
  state_->TakeSnapshot();  // window 1 starts at the start stance
  KeepSteps(n(), 0.1);
  state_->TakeSnapshot();  // window 2 starts, and fails
  ASSERT_TRUE(policy.RetryLonger("window 2: infeasible", state_.get()));
  EXPECT_EQ(state_->planned, 0);
  EXPECT_EQ(state_->plan.footsteps.size(), static_cast<size_t>(n()));
  EXPECT_TRUE(state_->snapshots.empty());
  EXPECT_EQ(policy.NextWindowSteps(*state_), 2 * window);
  EXPECT_EQ(state_->plan.horizon_retries, 1);
  EXPECT_EQ(state_->plan.message, "window 2: infeasible");

  // At the longest look a failure is final: nothing changes.
  state_->TakeSnapshot();
  EXPECT_FALSE(policy.RetryLonger("window 3: infeasible", state_.get()));
  EXPECT_EQ(state_->plan.horizon_retries, 1);
  EXPECT_EQ(state_->snapshots.size(), 1u);
}

TEST_F(HorizonPolicyTest, AFailureWhereOneFailedBeforeBacksUpOnlyItsOwnWindow) {
  SetUpContext(8);
  HorizonPolicy policy(*context_);
  const int window = context_->window_steps;
  KeepAWindow();
  KeepAWindow();
  state_->TakeSnapshot();  // window 3 starts at 2 n steps, and fails
  ASSERT_TRUE(policy.RetryLonger("window 3", state_.get()));
  EXPECT_EQ(state_->planned, n());  // back to window 2's start
  state_->TakeSnapshot();           // window 2 again, longer, fails where it failed before
  ASSERT_TRUE(policy.RetryLonger("window 4", state_.get()));
  EXPECT_EQ(state_->planned, n());  // its own start only
  EXPECT_EQ(policy.NextWindowSteps(*state_), 4 * window);
}

TEST_F(HorizonPolicyTest, KeptStepsPastTheFailureRestoreTheDefaultWindow) {
  SetUpContext(8);
  HorizonPolicy policy(*context_);
  const int window = context_->window_steps;
  KeepAWindow();
  state_->TakeSnapshot();
  ASSERT_TRUE(policy.RetryLonger("window 2", state_.get()));  // failed at n steps
  state_->TakeSnapshot();
  KeepSteps(n(), 0.1);  // the longer look ends where the failure was
  policy.OnStepsKept(state_.get(), n());
  EXPECT_EQ(policy.NextWindowSteps(*state_), 2 * window);
  EXPECT_TRUE(state_->plan.message.empty());
  KeepSteps(1, 0.1);  // past it
  policy.OnStepsKept(state_.get(), 1);
  EXPECT_EQ(policy.NextWindowSteps(*state_), window);
}

// A window whose plan takes the body into an obstacle is planned again from its own start
// (the loop then gives that window its body regions): the same horizon and lookahead, the
// retry counted and named; not at an eighth of the lookahead (no closer re-plan could
// follow a retry without a plan), nor once 50 retries are spent.
TEST_F(HorizonPolicyTest, AWindowWhoseBodyClashesIsPlannedAgainFromItsOwnStart) {
  SetUpContext(8);
  HorizonPolicy policy(*context_);
  const int window = context_->window_steps;
  KeepAWindow();
  state_->TakeSnapshot();  // window 2 starts at n steps; its plan clashes
  KeepSteps(n(), 0.1);
  ASSERT_TRUE(policy.RetryClearOfBody("window 2: the body clashes", state_.get()));
  EXPECT_EQ(state_->planned, n());
  EXPECT_EQ(state_->plan.footsteps.size(), static_cast<size_t>(2 * n()));
  EXPECT_EQ(policy.NextWindowSteps(*state_), window);
  EXPECT_EQ(policy.LookaheadScale(), 1.0);
  EXPECT_EQ(state_->plan.horizon_retries, 1);
  EXPECT_EQ(state_->plan.message, "window 2: the body clashes");
  for (int k = 0; k < 3; ++k) {  // half, a quarter, an eighth of the lookahead
    state_->TakeSnapshot();
    ASSERT_TRUE(policy.ReplanCloser("closer", state_.get()));
  }
  state_->TakeSnapshot();
  EXPECT_FALSE(policy.RetryClearOfBody("at an eighth", state_.get()));
  EXPECT_EQ(state_->plan.horizon_retries, 4);
  policy.OnStepsKept(state_.get(), n());  // a kept window: the whole lookahead again
  state_->plan.horizon_retries = 50;
  state_->TakeSnapshot();
  const size_t snapshots = state_->snapshots.size();
  EXPECT_FALSE(policy.RetryClearOfBody("window 2 again", state_.get()));
  EXPECT_EQ(state_->plan.horizon_retries, 50);
  EXPECT_EQ(state_->snapshots.size(), snapshots);  // nothing backed up
}

TEST_F(HorizonPolicyTest, AWindowThatKeepsNoStepOrOnlyShufflesIsStuck) {
  SetUpContext(2);
  HorizonPolicy policy(*context_);
  const double d_lim = course_->robot.d_lim_m;
  state_->plan.windows = 1;
  const std::optional<std::string> none = policy.Stuck(*state_, 0);
  ASSERT_TRUE(none.has_value());
  EXPECT_EQ(*none, "window 1 found no step that improves on standing still");

  state_->TakeSnapshot();
  KeepSteps(n(), 0.05 * d_lim);
  state_->TakeSnapshot();
  KeepSteps(n(), 0.04 * d_lim);  // 0.09 d_lim over two windows
  state_->plan.windows = 2;
  const std::optional<std::string> shuffled = policy.Stuck(*state_, n());
  ASSERT_TRUE(shuffled.has_value());
  EXPECT_NE(shuffled->find("window 2 only shuffled the feet"), std::string::npos) << *shuffled;

  state_->TakeSnapshot();
  KeepSteps(n(), 0.5 * d_lim);  // a window that walks
  EXPECT_FALSE(policy.Stuck(*state_, n()).has_value());
}

TEST_F(HorizonPolicyTest, AWayLeftThatStopsShrinkingStallsThePlanWhichKeepsItsBestPoint) {
  SetUpContext(2);
  ASSERT_EQ(options_.max_windows_without_progress, 3);
  HorizonPolicy policy(*context_);
  const double d_lim = course_->robot.d_lim_m;
  const double gain = MinProgressGain(*context_);
  // Each window moves every foot by dx along the route (+x toward the goal).
  auto window = [&](double dx) {
    state_->TakeSnapshot();
    KeepSteps(n(), dx);
    ++state_->plan.windows;
    state_->NoteProgress(RemainingWay(*context_, state_->plan.footsteps), gain);
  };
  window(0.5 * d_lim);
  window(0.5 * d_lim);
  EXPECT_EQ(state_->windows_without_progress, 0);
  const size_t best_size = state_->plan.footsteps.size();
  EXPECT_EQ(state_->best_window, 2);
  window(-0.4 * d_lim);  // back, forth, and not quite as far again: marking time
  window(0.3 * d_lim);
  EXPECT_FALSE(policy.Stalled(*state_).has_value());
  window(0.09 * d_lim);  // 0.01 d_lim short of the best point
  const std::optional<std::string> stalled = policy.Stalled(*state_);
  ASSERT_TRUE(stalled.has_value());
  EXPECT_NE(stalled->find("no progress in 3 windows"), std::string::npos) << *stalled;
  EXPECT_NE(stalled->find("after window 2"), std::string::npos) << *stalled;
  ASSERT_TRUE(state_->ReturnToBest());
  EXPECT_EQ(state_->plan.footsteps.size(), best_size);
  EXPECT_EQ(state_->planned, 2 * n());
  EXPECT_FALSE(state_->ReturnToBest());  // there already

  // A gain of the least progress resets the count.
  SetUpContext(2);
  window(0.5 * d_lim);
  window(-0.2 * d_lim);
  window(0.2 * d_lim + 1.5 * gain);
  EXPECT_EQ(state_->windows_without_progress, 0);
}

TEST_F(HorizonPolicyTest, AnInfeasibleWindowAtTheLongestLookIsPlannedAgainFromTheWindowBefore) {
  SetUpContext(2);
  HorizonPolicy policy(*context_);
  state_->TakeSnapshot();
  KeepSteps(n(), 0.1);
  state_->TakeSnapshot();
  KeepSteps(n(), 0.1);
  state_->TakeSnapshot();  // window 3 starts at 2 n steps and fails
  ASSERT_TRUE(policy.RetryLonger("window 3: infeasible", state_.get(), true));  // doubles the horizon
  EXPECT_EQ(state_->planned, n());
  state_->TakeSnapshot();
  // At the longest look, a window cut by its time ends the plan; one proven infeasible
  // is planned again from the start of the window before.
  EXPECT_FALSE(policy.RetryLonger("window 4: no_solution", state_.get(), false));
  ASSERT_TRUE(policy.RetryLonger("window 4: infeasible", state_.get(), true));
  EXPECT_EQ(state_->planned, 0);
  EXPECT_EQ(policy.NextWindowSteps(*state_), 2 * context_->window_steps);
  // From the start there is no earlier point.
  state_->TakeSnapshot();
  EXPECT_FALSE(policy.RetryLonger("window 5: infeasible", state_.get(), true));
}

}  // namespace
}  // namespace mfp
