// The polisher (planner/window_polisher.h) and the one body yaw: plans checked from
// their footsteps alone with exact R(yaw) (MeasureExactExcess, ValidatePlan).
#include <gtest/gtest.h>

#include <cmath>

#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/exact_window.h"
#include "planner/planning/internal/window_polisher.h"
#include "planner/planning/plan_validation.h"
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

  // No time to polish: the window is planned again with boxes shrunk by the chords'
  // error, whose footsteps are exact without the polisher, and the plan says so.
  options.polish.time_limit_s = 1e-9;
  reports.clear();
  const Plan replanned = PlanFootsteps(c.robot, c.regions, c.request, options, *solver,
                                       [&](const PlanProgress& p) { reports.push_back(p.polish); });
  ASSERT_TRUE(HasPlan(replanned.status)) << replanned.message;
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_TRUE(reports[0].exact);
  EXPECT_NE(replanned.message.find("re-planned with l_bnd and d_lim shrunk"), std::string::npos) << replanned.message;
  EXPECT_LE(LargestBoxExcess(c, replanned), 1e-6);

  // ... and with the re-plan turned off, the window keeps the MIQP's plan and says so.
  options.polish.replan_when_inexact = false;
  reports.clear();
  const Plan kept = PlanFootsteps(c.robot, c.regions, c.request, options, *solver,
                                  [&](const PlanProgress& p) { reports.push_back(p.polish); });
  ASSERT_TRUE(HasPlan(kept.status));
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_FALSE(reports[0].accepted);
  EXPECT_FALSE(reports[0].exact);
  EXPECT_NE(kept.message.find("kept the MIQP's plan"), std::string::npos) << kept.message;
  EXPECT_GT(LargestBoxExcess(c, kept), 1e-5);
}

TEST(WindowPolisher, ChordErrorBoundCoversEveryYawOfTheGrid) {
  // |(R_chords(theta) - R(theta)) o|_inf over a fine sweep of every segment and every
  // leg: within the bound, and the bound not more than 2x the worst seen.
  const Course c = LoadCourse("hexapod_stepping_stones_90.yaml");
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  const double bound = ChordErrorBound(formulation);
  const std::vector<double>& bp = formulation.yaw_breakpoints();
  ASSERT_GE(bp.size(), 2u);
  double worst = 0.0;
  for (size_t k = 0; k + 1 < bp.size(); ++k) {
    const Chord s = ChordOf(true, bp[k], bp[k + 1]), co = ChordOf(false, bp[k], bp[k + 1]);
    for (int j = 0; j <= 1000; ++j) {
      const double t = bp[k] + (bp[k + 1] - bp[k]) * j / 1000.0;
      const double ds = s.At(t) - std::sin(t), dc = co.At(t) - std::cos(t);
      for (const LegModel& leg : c.robot.legs) {
        const Eigen::Vector2d o = leg.nominal_offset_body_m;
        worst = std::max({worst, std::abs(dc * o.x() - ds * o.y()), std::abs(ds * o.x() + dc * o.y())});
      }
    }
  }
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.5 * bound);
}

TEST(WindowPolisher, AWindowPlannedWithinTheChordErrorIsExactWithoutThePolisher) {
  // The first window of the hexapod stones, planned with l_bnd and d_lim shrunk by
  // ChordErrorBound: the MIQP's own footsteps (chords, no polish) meet the true boxes
  // with exact R(yaw); the same window's unshrunk MIQP footsteps do not.
  const Course c = LoadCourse("hexapod_stepping_stones_45.yaml");
  const PlannerOptions& options = c.scenario.options;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, options), options.formulation);
  const auto solver = MakeRelaxationSolver(options.solvers.backend);
  BranchAndBoundOptions bnb = options.branch_and_bound;
  bnb.time_limit_s = 60.0;
  PolishOptions no_polish;
  no_polish.enabled = false;
  const ExactReplan replan = ReplanWithinChordError(formulation, {solver.get()}, bnb, no_polish);
  ASSERT_TRUE(replan.planned) << replan.note;
  EXPECT_NEAR(replan.shrink_m, ChordErrorBound(formulation), 1e-5);
  Plan shrunk;
  shrunk.footsteps = replan.formulation->ExtractFootsteps(replan.result.x);
  EXPECT_LE(LargestBoxExcess(c, shrunk), 0.0);
  const BranchAndBoundResult plain = SolveBranchAndBound(formulation.miqp(), *solver, bnb);
  ASSERT_TRUE(HasPlan(plain.status));
  Plan chords;
  chords.footsteps = formulation.ExtractFootsteps(plain.x);
  EXPECT_GT(LargestBoxExcess(c, chords), 1e-4);
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
