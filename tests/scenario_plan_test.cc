// Every scenario in config/scenarios/ plans to its goal, and the plan is re-checked
// constraint by constraint from its footsteps alone (ValidatePlan): each footstep inside
// its region, both reachability boxes, height change, yaw change, gait order, goal.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/relax_and_fix.h"
#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

std::vector<std::string> ScenarioFiles() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(MFP_SOURCE_DIR) + "/config/scenarios")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class ScenarioPlan : public ::testing::TestWithParam<std::string> {};

TEST_P(ScenarioPlan, ReachesTheGoalAndEveryConstraintHolds) {
  const Scenario scenario = LoadScenario(GetParam());
  const RobotModel robot = LoadRobot(scenario.robot_path);
  const std::vector<ConvexRegion> regions = ScenarioRegions(scenario, robot);
  ASSERT_FALSE(regions.empty());
  PlanRequest request = ScenarioRequest(scenario, robot, regions);
  // Generous, so that a slow machine changes the time taken, not the outcome.
  request.time_limit_s = 300.0;
  const auto solver = MakeRelaxationSolver(scenario.options.solvers.backend);
  const Plan plan = PlanFootsteps(robot, regions, request, scenario.options, *solver);
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  EXPECT_TRUE(plan.reaches_goal) << plan.message;
  const int n = robot.num_legs();
  ASSERT_GE(static_cast<int>(plan.footsteps.size()), n);
  EXPECT_GT(static_cast<int>(plan.footsteps.size()), n) << "no step planned";
  EXPECT_LE(static_cast<int>(plan.footsteps.size()) - n, request.max_steps > 0 ? request.max_steps : 12 * n);

  // Exact trigonometry, no slack for the MIQP's chords: the polisher met every box.
  const ValidationTolerances tol;
  const GoalSpec goal{scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad,
                      scenario.options.goal_tolerance_m, scenario.options.goal_yaw_tolerance_rad};
  const std::vector<std::string> violations = ValidatePlan(robot, regions, plan, goal, tol);
  for (const std::string& v : violations) ADD_FAILURE() << v;
  const ExactExcess excess = MeasureExactExcess(robot, regions, plan);
  EXPECT_LE(excess.reference_box_m, 1e-6);
  EXPECT_LE(excess.reachability_box_m, 1e-6);
  // No window kept the MIQP's inexact plan (a window re-planned within the chords' error,
  // exact_window.h, is exact and may be named in the message).
  EXPECT_EQ(plan.message.find("kept the MIQP's plan"), std::string::npos) << plan.message;
  EXPECT_EQ(plan.message.find("could not make it exact"), std::string::npos) << plan.message;
  // The start stance is the first n footsteps, each leg once, in gait order.
  for (int i = 0; i < n; ++i) EXPECT_EQ(plan.footsteps[i].leg, robot.gait[i]);
  // The last n footsteps are the final stance: each leg exactly once.
  std::vector<int> final_legs;
  for (size_t i = plan.footsteps.size() - n; i < plan.footsteps.size(); ++i) final_legs.push_back(plan.footsteps[i].leg);
  std::sort(final_legs.begin(), final_legs.end());
  for (int k = 0; k < n; ++k) EXPECT_EQ(final_legs[k], k);
}

INSTANTIATE_TEST_SUITE_P(AllScenarios, ScenarioPlan, ::testing::ValuesIn(ScenarioFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return std::filesystem::path(info.param).stem().string();
                         });

TEST(ScenarioPlanWorkers, TwoWorkersProveTheSameFirstWindowOptimum) {
  // The first window's MIQP of the hexapod stones, solved by one and by two workers
  // (both to the default gap): the same optimum, and the whole plan still valid.
  Course c = LoadCourse("hexapod_stepping_stones_45.yaml");
  c.request.time_limit_s = 300.0;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  BranchAndBoundOptions bnb = c.scenario.options.branch_and_bound;
  bnb.time_limit_s = 300.0;
  double objective[2];
  for (int threads = 1; threads <= 2; ++threads) {
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, threads);
    const BranchAndBoundResult r = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb);
    ASSERT_EQ(ToString(r.status), "optimal") << threads << " workers";
    objective[threads - 1] = r.objective;
  }
  EXPECT_NEAR(objective[1], objective[0], 2 * bnb.relative_gap * std::abs(objective[0]));

  PlannerOptions options = c.scenario.options;
  options.solvers.threads = 2;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, options, solvers.workers());
  ASSERT_TRUE(plan.reaches_goal) << plan.message;
  const ValidationTolerances tol;
  const GoalSpec goal{c.scenario.goal.x_m, c.scenario.goal.y_m, c.scenario.goal.yaw_rad, options.goal_tolerance_m,
                      options.goal_yaw_tolerance_rad};
  for (const std::string& v : ValidatePlan(c.robot, c.regions, plan, goal, tol)) ADD_FAILURE() << v;
}

TEST(ScenarioPlanFormulation, YawSegmentsOutOfReachLeaveTheOptimumAlone) {
  // The hexapod turns 45 degrees: its first configurations cannot reach the whole yaw
  // range, so clip_yaw_to_reach leaves out segments; the optimum must not move.
  Course c = LoadCourse("hexapod_stepping_stones_45.yaml");
  BranchAndBoundOptions bnb = c.scenario.options.branch_and_bound;
  bnb.time_limit_s = 300.0;
  const auto solver = MakeRelaxationSolver(c.scenario.options.solvers.backend);
  double objective[2];
  int integers[2];
  for (int clip = 0; clip < 2; ++clip) {
    FormulationOptions options = c.scenario.options.formulation;
    options.clip_yaw_to_reach = clip == 1;
    const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options), options);
    const BranchAndBoundResult r = SolveBranchAndBound(formulation.miqp(), *solver, bnb);
    ASSERT_EQ(ToString(r.status), "optimal") << "clip " << clip;
    objective[clip] = r.objective;
    integers[clip] = formulation.miqp().num_integer();
  }
  EXPECT_LT(integers[1], integers[0]);
  EXPECT_NEAR(objective[1], objective[0], 2 * bnb.relative_gap * std::abs(objective[0]));
}

TEST(ScenarioPlanWindows, MaxWindowsOneSolvesExactlyTheFirstWindow) {
  Course c = LoadCourse("littledog_stepping_stones_45.yaml");
  c.request.time_limit_s = 300.0;
  c.request.max_windows = 1;
  const auto solver = MakeRelaxationSolver(c.scenario.options.solvers.backend);
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, c.scenario.options, *solver);
  ASSERT_TRUE(HasPlan(plan.status)) << plan.message;
  EXPECT_EQ(plan.windows, 1);
  EXPECT_FALSE(plan.reaches_goal);
  EXPECT_NE(plan.message.find("1 window"), std::string::npos) << plan.message;
  EXPECT_LE(static_cast<int>(plan.footsteps.size()) - c.robot.num_legs(), 2 * c.robot.num_legs());

  c.request.max_windows = -1;
  const Plan rejected = PlanFootsteps(c.robot, c.regions, c.request, c.scenario.options, *solver);
  EXPECT_EQ(rejected.status, SolveStatus::kInvalidRequest);
  EXPECT_NE(rejected.message.find("max_windows"), std::string::npos) << rejected.message;
}

}  // namespace
}  // namespace mfp
