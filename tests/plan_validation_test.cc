// ValidatePlan catches each kind of violation in an otherwise valid plan.
#include "planner/planning/plan_validation.h"

#include <gtest/gtest.h>

#include <utility>

#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {
namespace {

TEST(PlanValidation, CatchesEachKindOfViolation) {
  // A valid plan of the flat hexapod scenario, then one defect at a time.
  const Scenario scenario = LoadScenario(std::string(MFP_SOURCE_DIR) + "/config/scenarios/littledog_flat.yaml");
  const RobotModel robot = LoadRobot(scenario.robot_path);
  const std::vector<ConvexRegion> regions = ScenarioRegions(scenario, robot);
  PlanRequest request = ScenarioRequest(scenario, robot, regions);
  request.max_steps = 8;
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  const Plan plan = PlanFootsteps(robot, regions, request, scenario.options, *solver);
  ASSERT_TRUE(HasPlan(plan.status));
  ASSERT_EQ(plan.footsteps.size(), 12u);
  const ValidationTolerances tol;  // exact trigonometry
  const GoalSpec goal{scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad};
  ASSERT_TRUE(ValidatePlan(robot, regions, plan, goal, tol).empty());
  auto expect_violation = [&](const Plan& bad, const std::string& what) {
    const auto errors = ValidatePlan(robot, regions, bad, goal, tol);
    bool found = false;
    for (const auto& e : errors) found = found || e.find(what) != std::string::npos;
    EXPECT_TRUE(found) << "expected a '" << what << "' violation";
  };
  Plan bad = plan;
  bad.footsteps[6].position_world_m.x() += 0.25;  // beyond both boxes
  expect_violation(bad, "reachability box");
  bad = plan;
  bad.footsteps[6].position_world_m.z() += 0.2;
  expect_violation(bad, "height change");
  expect_violation(bad, "outside region");
  bad = plan;
  bad.footsteps[7].yaw_rad += 1.0;
  expect_violation(bad, "yaw change");
  bad = plan;
  std::swap(bad.footsteps[5].leg, bad.footsteps[6].leg);
  expect_violation(bad, "gait order");
  bad = plan;
  bad.footsteps[8].region_id = 99;
  expect_violation(bad, "does not exist");
  bad = plan;
  bad.reaches_goal = true;  // eight steps do not reach a goal 0.6 m away
  expect_violation(bad, "goal");
}

}  // namespace
}  // namespace mfp
