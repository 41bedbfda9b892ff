// Replanning from the previous plan (planner/planning/internal/warm_start.h): a robot that walked
// one gait cycle of its plan asks again; the previous plan seeds the search, which must
// find the same optimum as a search from scratch, and a bounded replan still answers a
// valid plan.
#include <gtest/gtest.h>

#include <cmath>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/warm_start.h"
#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

// The stance after walking the plan's first gait cycle, in leg order.
std::vector<Eigen::Vector3d> AfterFirstCycle(const RobotModel& robot, const Plan& plan) {
  const int n = robot.num_legs();
  std::vector<Eigen::Vector3d> feet(static_cast<size_t>(n));
  for (int k = n; k < 2 * n; ++k) {
    const Footstep& f = plan.footsteps[static_cast<size_t>(k)];
    feet[static_cast<size_t>(f.leg)] = f.position_world_m;
  }
  return feet;
}

class WarmStartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    c_ = LoadCourse("hexapod_stepping_stones_90.yaml");
    c_.request.max_steps = 2 * c_.robot.num_legs();  // one window, as a replanning robot asks
    c_.request.time_limit_s = 300.0;
    solver_ = MakeRelaxationSolver(c_.scenario.options.solvers.backend);
    first_ = PlanFootsteps(c_.robot, c_.regions, c_.request, c_.scenario.options, *solver_);
    ASSERT_TRUE(HasPlan(first_.status)) << first_.message;
    ASSERT_EQ(static_cast<int>(first_.footsteps.size()), 3 * c_.robot.num_legs());
    replan_ = c_.request;
    replan_.start_feet_world_m = AfterFirstCycle(c_.robot, first_);
    replan_.start_yaw_rad = first_.footsteps[static_cast<size_t>(2 * c_.robot.num_legs() - 1)].yaw_rad;
  }
  Course c_;
  std::unique_ptr<RelaxationSolver> solver_;
  Plan first_;
  PlanRequest replan_;
};

TEST_F(WarmStartTest, TheStepsAheadOfTheRobotBecomeProposals) {
  const MiqpFormulation formulation(FirstWindowProblem(c_.robot, c_.regions, replan_, c_.scenario.options),
                                    c_.scenario.options.formulation);
  const WarmStart warm = WarmStartFrom(formulation, first_.footsteps, 0.05);
  EXPECT_TRUE(warm.stance_matched);
  ASSERT_FALSE(warm.proposals.empty());
  for (const Eigen::VectorXd& x : warm.proposals) {
    ASSERT_EQ(x.size(), formulation.miqp().num_variables());
    // The first new configuration stands where the previous plan's second one did.
    for (int i = c_.robot.num_legs(); i < 2 * c_.robot.num_legs(); ++i) {
      const Footstep& before = first_.footsteps[static_cast<size_t>(i + c_.robot.num_legs())];
      int chosen = -1;
      for (size_t r = 0; r < formulation.problem().regions.size(); ++r) {
        const int h = formulation.vars().region[static_cast<size_t>(i)][r];
        if (h >= 0 && x(h) > 0.5) chosen = formulation.problem().regions[r].id;
      }
      EXPECT_EQ(chosen, before.region_id) << "step " << i;
    }
  }
  // A robot that is not where the plan put it gets no warm start.
  PlanRequest moved = replan_;
  for (Eigen::Vector3d& f : moved.start_feet_world_m) f.x() -= 0.1;
  const MiqpFormulation elsewhere(FirstWindowProblem(c_.robot, c_.regions, moved, c_.scenario.options),
                                  c_.scenario.options.formulation);
  const WarmStart none = WarmStartFrom(elsewhere, first_.footsteps, 0.05);
  EXPECT_FALSE(none.stance_matched);
  EXPECT_TRUE(none.proposals.empty());
}

TEST_F(WarmStartTest, AWarmStartedSearchFindsTheSameOptimum) {
  const Plan cold = PlanFootsteps(c_.robot, c_.regions, replan_, c_.scenario.options, *solver_);
  PlanRequest warm_request = replan_;
  warm_request.warm_start = {first_.footsteps};
  PlannerOptions options = c_.scenario.options;
  options.replan_time_s = 0.0;  // the whole search: same problem, same optimum
  const Plan warm = PlanFootsteps(c_.robot, c_.regions, warm_request, options, *solver_);
  ASSERT_TRUE(HasPlan(cold.status)) << cold.message;
  ASSERT_TRUE(HasPlan(warm.status)) << warm.message;
  const double tolerance = 2 * options.branch_and_bound.relative_gap * std::max(1.0, std::abs(cold.objective));
  EXPECT_NEAR(warm.objective, cold.objective, tolerance);
}

TEST_F(WarmStartTest, ABoundedReplanAnswersAValidPlan) {
  PlanRequest warm_request = replan_;
  warm_request.warm_start = {first_.footsteps};
  PlannerOptions options = c_.scenario.options;
  options.replan_time_s = 1e-3;  // far too short to prove anything: the warm plan is the answer
  const Plan plan = PlanFootsteps(c_.robot, c_.regions, warm_request, options, *solver_);
  ASSERT_TRUE(HasPlan(plan.status)) << plan.message;
  EXPECT_NE(plan.status, SolveStatus::kTimeLimit) << "the request's own limit was not reached";
  EXPECT_GT(plan.footsteps.size(), static_cast<size_t>(c_.robot.num_legs()));
  const GoalSpec goal{c_.scenario.goal.x_m, c_.scenario.goal.y_m, c_.scenario.goal.yaw_rad,
                      options.goal_tolerance_m, options.goal_yaw_tolerance_rad};
  for (const std::string& v : ValidatePlan(c_.robot, c_.regions, plan, goal, ValidationTolerances()))
    ADD_FAILURE() << v;
}

}  // namespace
}  // namespace mfp
