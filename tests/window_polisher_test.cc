// The polisher (planner/window_polisher.h) and the one body yaw: plans checked from
// their footsteps alone with exact R(yaw) (MeasureExactExcess, ValidatePlan).
#include <gtest/gtest.h>

#include <cmath>

#include "planner/formulation/miqp_formulation.h"
#include "planner/io/robot_loader.h"
#include "planner/io/scenario_yaml.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/planning/window_polisher.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {
namespace {

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
  c.request.time_limit_s = 120.0;  // generous: a slow machine changes the time, not the plan
  return c;
}

Plan PlanCourse(const Course& c, const PlannerOptions& options) {
  const auto solver = MakeRelaxationSolver(options.solvers.backend);
  return PlanFootsteps(c.robot, c.regions, c.request, options, *solver);
}

double LargestBoxExcess(const Course& c, const Plan& plan) {
  const ExactExcess e = MeasureExactExcess(c.robot, c.regions, plan);
  return std::max(e.reference_box_m, e.reachability_box_m);
}

TEST(WindowPolisher, StonesPlanMeetsTheBoxesWithExactRotationOnlyWhenPolished) {
  const Course c = LoadCourse("littledog_stepping_stones_45.yaml");
  PlannerOptions options = c.scenario.options;
  options.polish.enabled = false;
  const Plan chords = PlanCourse(c, options);
  ASSERT_TRUE(HasPlan(chords.status)) << chords.message;
  // The chords of sin/cos leave footsteps outside their boxes once R(yaw) is exact.
  EXPECT_GT(LargestBoxExcess(c, chords), 1e-4);

  options.polish.enabled = true;
  const Plan polished = PlanCourse(c, options);
  ASSERT_TRUE(HasPlan(polished.status)) << polished.message;
  EXPECT_TRUE(polished.reaches_goal) << polished.message;
  EXPECT_TRUE(polished.message.empty()) << polished.message;
  EXPECT_LE(LargestBoxExcess(c, polished), 1e-6);
  const GoalSpec goal{c.scenario.goal.x_m, c.scenario.goal.y_m, c.scenario.goal.yaw_rad,
                      options.goal_tolerance_m, options.goal_yaw_tolerance_rad};
  for (const std::string& v : ValidatePlan(c.robot, c.regions, polished, goal, ValidationTolerances{})) ADD_FAILURE() << v;
}

TEST(WindowPolisher, ReportsEachWindowAndFallsBackWithAMessageWhenOutOfTime) {
  Course c = LoadCourse("littledog_flat.yaml");
  c.request.max_steps = 8;
  PlannerOptions options = c.scenario.options;
  std::vector<PolishReport> reports;
  const auto solver = MakeRelaxationSolver(options.solvers.backend);
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, options, *solver,
                                  [&](const PlanProgress& p) { reports.push_back(p.polish); });
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_TRUE(reports[0].attempted);
  EXPECT_TRUE(reports[0].accepted) << reports[0].message;
  EXPECT_GT(reports[0].excess_before, 1e-5);  // the MIQP's chords
  EXPECT_LE(reports[0].excess_after, 1e-6);
  EXPECT_GT(reports[0].time_s, 0.0);

  // No time to polish: the window keeps the MIQP's plan and the plan says so.
  options.polish.time_limit_s = 1e-9;
  reports.clear();
  const Plan kept = PlanFootsteps(c.robot, c.regions, c.request, options, *solver,
                                  [&](const PlanProgress& p) { reports.push_back(p.polish); });
  ASSERT_TRUE(HasPlan(kept.status));
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_FALSE(reports[0].accepted);
  EXPECT_NE(kept.message.find("kept the MIQP's plan"), std::string::npos) << kept.message;
  EXPECT_GT(LargestBoxExcess(c, kept), 1e-5);
}

TEST(WindowPolisher, AWindowThatTrimsEveryStepHasNothingToSolve) {
  // Every step trimmed: each configuration holds the start yaw and every foot stays, so
  // the polisher has no variable; it returns the MIQP's footsteps (once it aborted).
  const Course c = LoadCourse("littledog_flat.yaml");
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(formulation.miqp().num_variables());
  for (int i = formulation.num_legs(); i < formulation.num_steps(); ++i) {
    x(formulation.vars().trim[i]) = 1.0;
    x(formulation.vars().region[i][0]) = 1.0;
  }
  const PolishedWindow polished = PolishWindow(formulation, x, PolishOptions{});
  EXPECT_FALSE(polished.report.attempted);
  ASSERT_EQ(static_cast<int>(polished.footsteps.size()), formulation.num_steps());
  for (int i = formulation.num_legs(); i < formulation.num_steps(); ++i) {
    EXPECT_EQ(polished.footsteps[i].position_world_m, formulation.ExtractFootsteps(x)[i].position_world_m);
  }
}

TEST(BodyYaw, ATurnedGoalIsReachedOnlyByTheYawTheFinalFootstepsReport) {
  // A flat walk to a goal turned 0.3 rad: the plan's final yaw (its last footstep's) is
  // within the goal's yaw tolerance, and every footstep's boxes hold with its own yaw.
  Course c = LoadCourse("littledog_flat.yaml");
  c.request.goal_yaw_rad = 0.3;
  const PlannerOptions& options = c.scenario.options;
  const Plan plan = PlanCourse(c, options);
  ASSERT_TRUE(plan.reaches_goal) << plan.message;
  EXPECT_DOUBLE_EQ(FinalStanceYaw(c.robot, plan.footsteps), plan.footsteps.back().yaw_rad);
  EXPECT_LE(std::abs(plan.footsteps.back().yaw_rad - 0.3), options.goal_yaw_tolerance_rad);
  const GoalSpec goal{c.request.goal_x_m, c.request.goal_y_m, 0.3, options.goal_tolerance_m,
                      options.goal_yaw_tolerance_rad};
  for (const std::string& v : ValidatePlan(c.robot, c.regions, plan, goal, ValidationTolerances{})) ADD_FAILURE() << v;
  // The validator judges the goal by that yaw too: a plan whose last yaw misses the goal
  // yaw does not pass as reaching it.
  Plan turned = plan;
  for (size_t i = turned.footsteps.size() - c.robot.num_legs(); i < turned.footsteps.size(); ++i) {
    turned.footsteps[i].yaw_rad = 0.0;
  }
  bool flagged = false;
  for (const std::string& v : ValidatePlan(c.robot, c.regions, turned, goal, ValidationTolerances{})) {
    flagged = flagged || v.find("goal yaw") != std::string::npos;
  }
  EXPECT_TRUE(flagged);
}

}  // namespace
}  // namespace mfp
