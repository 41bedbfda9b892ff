// Every scenario in config/scenarios/ plans to its goal, and the plan is re-checked
// constraint by constraint from its footsteps alone (ValidatePlan): each footstep inside
// its region, both reachability boxes, height change, yaw change, gait order, goal.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "planner/branch_and_bound.h"
#include "planner/footstep_planner.h"
#include "planner/miqp_formulation.h"
#include "planner/plan_validation.h"
#include "planner/relax_and_fix.h"
#include "planner/relaxation_solver_factory.h"
#include "planner/robot_loader.h"
#include "planner/scenario_yaml.h"

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

// A scenario of config/scenarios/ loaded with its robot, regions and request.
struct Course {
  Scenario scenario;
  RobotModel robot;
  std::vector<ConvexRegion> regions;
  PlanRequest request;
};

Course LoadCourse(const std::string& file_name) {
  Course c;
  c.scenario = LoadScenario(std::string(MFP_SOURCE_DIR) + "/config/scenarios/" + file_name);
  c.robot = LoadRobot(c.scenario.robot_path);
  c.regions = ScenarioRegions(c.scenario, c.robot);
  c.request = ScenarioRequest(c.scenario, c.robot, c.regions);
  return c;
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
  const auto solver = MakeRelaxationSolver(scenario.options.relaxation_solver);
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
  EXPECT_TRUE(plan.message.empty()) << plan.message;  // no window fell back to the MIQP's plan
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
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.relaxation_solver, threads);
    const BranchAndBoundResult r = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb);
    ASSERT_EQ(ToString(r.status), "optimal") << threads << " workers";
    objective[threads - 1] = r.objective;
  }
  EXPECT_NEAR(objective[1], objective[0], 2 * bnb.relative_gap * std::abs(objective[0]));

  PlannerOptions options = c.scenario.options;
  options.threads = 2;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.relaxation_solver, options.threads);
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
  const auto solver = MakeRelaxationSolver(c.scenario.options.relaxation_solver);
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

TEST(RelaxAndFix, FindsAFeasiblePlanNearTheProvenOptimum) {
  // The hexapod stones with 24 new steps (Table I): relax-and-fix fixes the four
  // configurations one at a time. Its plan must meet every row and bound with integral
  // choices and lie within 1 % of the optimum the branch-and-bound proves (measured: 0 %).
  Course c = LoadCourse("hexapod_stepping_stones_45.yaml");
  c.request.window_steps = 24;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.relaxation_solver, 1);
  RelaxAndFixOptions rf;
  rf.stage = c.scenario.options.branch_and_bound;
  rf.time_limit_s = 300.0;
  const RelaxAndFixResult r = RelaxAndFix(formulation, solvers.workers(), rf);
  ASSERT_TRUE(r.x.has_value());
  EXPECT_EQ(r.stages, formulation.num_blocks() - 1);
  const Miqp& m = formulation.miqp();
  EXPECT_LE(m.MaxViolation(*r.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*r.x), 0.0);

  BranchAndBoundOptions bnb = c.scenario.options.branch_and_bound;
  bnb.time_limit_s = 300.0;
  const BranchAndBoundResult proof = SolveBranchAndBound(m, solvers.workers(), bnb);
  ASSERT_EQ(ToString(proof.status), "optimal");
  EXPECT_GE(m.Objective(*r.x), proof.bound - 1e-6);
  EXPECT_LE(m.Objective(*r.x), proof.objective + 0.01 * std::abs(proof.objective));

  // Stopped after one stage (as when its time runs out), the configurations left are
  // rounded: still a complete plan that meets every row, no better than the optimum.
  rf.max_searched_stages = 1;
  const RelaxAndFixResult partial = RelaxAndFix(formulation, solvers.workers(), rf);
  ASSERT_TRUE(partial.x.has_value());
  EXPECT_TRUE(partial.completed_by_rounding);
  EXPECT_FALSE(r.completed_by_rounding);
  EXPECT_EQ(partial.stages, 1);
  EXPECT_LE(m.MaxViolation(*partial.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*partial.x), 0.0);
  EXPECT_GE(m.Objective(*partial.x), proof.bound - 1e-6);

  // A complete plan: integral choices that meet every row, within 1 % of the optimum.
  const auto expect_plan_near_optimum = [&](const RelaxAndFixResult& run) {
    ASSERT_TRUE(run.x.has_value());
    EXPECT_LE(m.MaxViolation(*run.x), 1e-5);
    EXPECT_EQ(m.MaxIntegrality(*run.x), 0.0);
    EXPECT_LE(m.Objective(*run.x), proof.objective + 0.01 * std::abs(proof.objective));
  };

  // The stages with the steps they have not reached in the full relaxation of their
  // region binaries (the hull is the default): also a complete plan within 1 %.
  rf.max_searched_stages = 0;
  rf.hull_for_later_steps = false;
  expect_plan_near_optimum(RelaxAndFix(formulation, solvers.workers(), rf));

  // With the search's rounding heuristic in the stages (off by default): rounding QPs
  // on top of the node relaxations, and still a complete plan within 1 %.
  rf.hull_for_later_steps = true;
  rf.stage_rounding = true;
  const RelaxAndFixResult rounded = RelaxAndFix(formulation, solvers.workers(), rf);
  expect_plan_near_optimum(rounded);
  EXPECT_GT(rounded.relaxations - rounded.nodes, r.relaxations - r.nodes);
  rf.stage_rounding = false;

  // Two paths side by side with two workers: the first is the one-worker run, so the
  // plan is never worse than that one, and it is a plan.
  rf.hull_for_later_steps = true;
  const RelaxAndFixResult one = RelaxAndFix(formulation, solvers.workers(), rf);
  const RelaxationSolverSet two_workers = MakeRelaxationSolvers(c.scenario.options.relaxation_solver, 2);
  const RelaxAndFixResult two = RelaxAndFixTwoPaths(formulation, two_workers.workers(), rf);
  ASSERT_TRUE(one.x.has_value());
  ASSERT_TRUE(two.x.has_value());
  EXPECT_LE(m.MaxViolation(*two.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*two.x), 0.0);
  EXPECT_LE(m.Objective(*two.x), m.Objective(*one.x) + 1e-9 * std::abs(m.Objective(*one.x)));
  EXPECT_EQ(two.stages, 2 * one.stages);
}

TEST(ScenarioPlanWindows, MaxWindowsOneSolvesExactlyTheFirstWindow) {
  Course c = LoadCourse("littledog_stepping_stones_45.yaml");
  c.request.time_limit_s = 300.0;
  c.request.max_windows = 1;
  const auto solver = MakeRelaxationSolver(c.scenario.options.relaxation_solver);
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
  const ValidationTolerances tol;
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
