// Issue 25: a plan that ends short of the goal names where it stopped and the place ahead
// that blocks it: the gap in the regions a leg's path must cross, its width against the
// most a step moves a foot on one axis (d_lim + l_bnd). Since stop 35 the route graph joins
// only gaps one step's move bridges, so a gap between that and its diagonal is `no_route`
// at once; a partial plan stops where one foot could bridge a gap and the body cannot.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "io/plan_json.h"
#include "planner/planning/internal/stop_report.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1, double z = 0.0) {
  return MakeRegionFromPolygon(id, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, 0.005);
}

class StopReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { course_ = new Course(LoadCourse("hexapod_flat.yaml")); }
  static void TearDownTestSuite() { delete course_; }
  static const RobotModel& robot() { return course_->robot; }
  static double StepSpan() { return robot().d_lim_m + robot().l_bnd_m; }
  // The hexapod's start stance at the origin on flat floor, facing +x, the goal at (goal_x, 0).
  static PlanRequest Request(double goal_x) {
    PlanRequest r = course_->request;
    for (Eigen::Vector3d& f : r.start_feet_world_m) f.z() = 0.0;
    r.goal_x_m = goal_x;
    r.goal_y_m = 0.0;
    r.goal_yaw_rad = 0.0;
    r.time_limit_s = 30.0;
    return r;
  }
  // One foot of each leg, where the leg stands in the nominal stance at (x, 0, yaw 0).
  static std::vector<Footstep> StanceAt(double x, int region_id) {
    std::vector<Footstep> feet;
    for (int leg = 0; leg < robot().num_legs(); ++leg) {
      Footstep f;
      f.leg = leg;
      f.position_world_m << NominalFootXY(robot(), leg, x, 0.0, 0.0), 0.0;
      f.region_id = region_id;
      feet.push_back(f);
    }
    return feet;
  }
  // A straight path of body centres from (x0, 0) to (x1, 0) at yaw 0.
  static StopPath Straight(double x0, double x1) {
    StopPath path;
    for (double x = x0; x <= x1 + 1e-9; x += 0.01) {
      path.centres_m.emplace_back(x, 0.0);
      path.yaws_rad.push_back(0.0);
    }
    return path;
  }
  static Course* course_;
};
Course* StopReportTest::course_ = nullptr;

TEST_F(StopReportTest, AGapWiderThanAStepOnAnAxisWithinItsDiagonalIsNoRouteNamingTheGap) {
  // Floor up to x = 0.7 and from x = 0.7 + gap on: wider than a step on the x axis, within
  // its diagonal. The region graph joins only what one step's move bridges (reach_polygon.h),
  // so the plan is refused at once, naming the gap and its width.
  const double gap = 0.5 * (StepSpan() + std::sqrt(2.0) * StepSpan());
  ASSERT_LT(gap, std::sqrt(2.0) * StepSpan());
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, 0.7, 1.0), Rect(1, 0.7 + gap, -1.0, 3.0, 1.0)};
  const PlanRequest request = Request(1.7 + gap);
  const PlannerOptions& options = course_->scenario.options;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  const Plan plan = PlanFootsteps(robot(), regions, request, options, solvers.workers());

  ASSERT_EQ(plan.status, SolveStatus::kNoRoute) << ToString(plan.status) << ": " << plan.message;
  std::ostringstream width;
  width.precision(3);
  width << "region 1, lies across a gap " << gap << " m wide";
  EXPECT_NE(plan.message.find(width.str()), std::string::npos) << plan.message;
  std::ostringstream span;
  span.precision(3);
  span << "spans " << StepSpan() << " m in that direction";
  EXPECT_NE(plan.message.find(span.str()), std::string::npos) << plan.message;
}

TEST_F(StopReportTest, APlanStoppedWhereOnlyOneFootCouldGoRoundAGapNamesTheGapAndTheDetour) {
  // A gap of one and a half steps, and a narrow stone within a step of both floors off the
  // legs' nominal paths: the region graph joins the floors through it (a foot can bridge),
  // the body cannot follow, and the plan stops short naming the gap and the stone.
  const double wide = 1.5 * StepSpan();
  const double x0 = 0.7, x1 = 0.7 + wide, stone_x = 0.5 * (x0 + x1);
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, x0, 1.0), Rect(1, x1, -1.0, 3.0, 1.0),
                                             Rect(7, stone_x - 0.02, 0.1, stone_x + 0.02, 0.25)};
  const PlanRequest request = Request(1.7 + wide);
  const PlannerOptions& options = course_->scenario.options;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  const Plan plan = PlanFootsteps(robot(), regions, request, options, solvers.workers());

  ASSERT_EQ(plan.status, SolveStatus::kPartial) << ToString(plan.status) << ": " << plan.message;
  ASSERT_TRUE(plan.stop.stopped);
  const PlanStopGap& g = plan.stop.gap;
  ASSERT_TRUE(g.found) << plan.message;
  EXPECT_TRUE(g.blocks);
  EXPECT_EQ(g.from_region, 0);
  EXPECT_EQ(g.to_region, 1);
  EXPECT_NEAR(g.step_span_m, StepSpan(), 1e-9);
  EXPECT_EQ(g.detour_region, 7);
  EXPECT_LT(plan.stop.centre_world_m.x(), x0);
  EXPECT_NE(plan.message.find("more than one step spans"), std::string::npos) << plan.message;
  const nlohmann::json json = PlanToJson(plan, robot(), regions);
  ASSERT_TRUE(json.contains("stop"));
  EXPECT_EQ(json["stop"]["gap"]["from_region"], 0);
  EXPECT_EQ(json["stop"]["gap"]["to_region"], 1);
  EXPECT_TRUE(json["stop"]["gap"]["blocks"].get<bool>());
}

TEST_F(StopReportTest, AGapWithinAStepIsTheWidestNamedAndDoesNotBlock) {
  const double gap = 0.5 * StepSpan();
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, 0.7, 1.0), Rect(1, 0.7 + gap, -1.0, 3.0, 1.0)};
  const PlanStopGap g = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline());
  ASSERT_TRUE(g.found);
  EXPECT_FALSE(g.blocks);
  EXPECT_NEAR(g.width_m, gap, 1e-6);
  EXPECT_EQ(g.from_region, 0);
  EXPECT_EQ(g.to_region, 1);
}

TEST_F(StopReportTest, AnExpiredDeadlineNamesNoGapRatherThanAnUnexaminedOne) {
  const double gap = 2.0 * StepSpan();
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, 0.7, 1.0), Rect(1, 0.7 + gap, -1.0, 3.0, 1.0)};
  const PlanStopGap open = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline());
  EXPECT_TRUE(open.found);
  const PlanStopGap cut =
      FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline::After(-1.0));
  EXPECT_FALSE(cut.found);
}

TEST_F(StopReportTest, AGapOfTwoStepsBeyondANarrowOneIsTheOneThatBlocks) {
  // A narrow gap first (within a step), then one of two steps: the second blocks.
  const double narrow = 0.3 * StepSpan(), wide = 2.0 * StepSpan();
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, 0.6, 1.0), Rect(1, 0.6 + narrow, -1.0, 1.5, 1.0),
                                             Rect(2, 1.5 + wide, -1.0, 4.0, 1.0)};
  const PlanStopGap g = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 3.0), StepSpan(), Deadline());
  ASSERT_TRUE(g.found);
  EXPECT_TRUE(g.blocks);
  EXPECT_EQ(g.from_region, 1);
  EXPECT_EQ(g.to_region, 2);
  EXPECT_NEAR(g.width_m, wide, 1e-6);
}

TEST_F(StopReportTest, AGapOneFootCouldGoRoundNamesTheRegionOfTheDetour) {
  // A gap of one and a half steps ahead, and between the legs' paths (y in [0.1, 0.25]) a
  // narrow stone within a step of both floors: one foot could go round through it.
  const double wide = 1.5 * StepSpan();
  const double x0 = 0.7, x1 = 0.7 + wide, stone_x = 0.5 * (x0 + x1);
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, x0, 1.0), Rect(1, x1, -1.0, 3.0, 1.0),
                                             Rect(7, stone_x - 0.02, 0.1, stone_x + 0.02, 0.25)};
  ASSERT_LT(stone_x - 0.02 - x0, StepSpan());
  const PlanStopGap g = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline());
  ASSERT_TRUE(g.found);
  EXPECT_TRUE(g.blocks);
  EXPECT_EQ(g.detour_region, 7);
  const PlanStop stop{true, Eigen::Vector3d::Zero(), 0.0, {0}, "no_progress", g};
  EXPECT_NE(StopText(robot(), stop).find("one foot could go round it only through region 7"), std::string::npos)
      << StopText(robot(), stop);
}

TEST_F(StopReportTest, ARiseBeyondDzMaxBlocksAGapWithinAStep) {
  const double gap = 0.5 * StepSpan();
  const double high = 2.0 * robot().dz_max_m;
  std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, 0.7, 1.0), Rect(1, 0.7 + gap, -1.0, 3.0, 1.0, high)};
  PlanStopGap g = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline());
  ASSERT_TRUE(g.found);
  EXPECT_TRUE(g.blocks);
  EXPECT_EQ(g.to_region, 1);
  EXPECT_NEAR(g.rise_m, high, 1e-6);
  const PlanStop stop{true, Eigen::Vector3d::Zero(), 0.0, {0}, "no_progress", g};
  EXPECT_NE(StopText(robot(), stop).find("more than dz_max"), std::string::npos) << StopText(robot(), stop);
  // A floor within dz_max under the high one is the support after the gap: nothing blocks.
  regions.push_back(Rect(2, 0.7 + gap, -1.0, 3.0, 1.0, 0.5 * robot().dz_max_m));
  g = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline());
  ASSERT_TRUE(g.found);
  EXPECT_FALSE(g.blocks);
  EXPECT_EQ(g.to_region, 2);
}

TEST_F(StopReportTest, APathThatLeavesTheRegionsForGoodBlocks) {
  const std::vector<ConvexRegion> regions = {Rect(0, -1.0, -1.0, 0.7, 1.0)};
  const PlanStopGap g = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 2.0), StepSpan(), Deadline());
  ASSERT_TRUE(g.found);
  EXPECT_TRUE(g.blocks);
  EXPECT_EQ(g.from_region, 0);
  EXPECT_EQ(g.to_region, -1);
  const PlanStop stop{true, Eigen::Vector3d::Zero(), 0.0, {0}, "no_progress", g};
  EXPECT_NE(StopText(robot(), stop).find("meets no region on the rest of the way"), std::string::npos);
  // A path that ends within a step of the last region (a goal spot just off it) is no blocker.
  const PlanStopGap end = FirstGapAhead(robot(), regions, StanceAt(0.0, 0), Straight(0.0, 0.7 - 0.42 + 0.1), StepSpan(), Deadline());
  EXPECT_FALSE(end.found && end.blocks);
}

TEST_F(StopReportTest, TheReportsSampleStepAndSampleCapAreOptions) {
  // DescribeStop samples the way ahead stop_report.step l_bnd apart, at most
  // stop_report.max_samples samples. A gap half an l_bnd wide (within a step, so named as
  // the widest gap, not a blocker) placed where no foot's sample at 4 l_bnd apart falls:
  // the default samples (a quarter of l_bnd apart) name it, those 4 l_bnd apart do not,
  // nor do two samples (the stance's and the way's midpoint's) on the way to x = 3.
  const PlanRequest request = Request(3.0);
  PlannerOptions options = course_->scenario.options;
  const double l_bnd = robot().l_bnd_m, gap = 0.5 * l_bnd;
  const std::vector<Footstep> feet = StanceAt(0.0, 0);
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Footstep& f : feet) centre += f.position_world_m.head<2>() / static_cast<double>(feet.size());
  const std::vector<RelaxationSolver*> no_solvers;
  std::vector<ConvexRegion> regions;
  auto named_gap = [&](const PlannerOptions& o) {
    PlanContext context(robot(), regions, request, o, no_solvers);
    context.usable = regions;
    Plan plan;
    plan.footsteps = feet;
    return DescribeStop(context, plan, "no_progress", Deadline()).gap;
  };
  // The feet's x at the two sparse ways' samples; the gap's start at least 1 mm clear of them.
  std::vector<double> coarse_feet_x;
  {
    const PlanContext context(robot(), regions, request, options, no_solvers);
    for (const StopPath& coarse : {PathAhead(context, centre, 0.0, 4.0 * l_bnd, options.stop_report_max_samples),
                                   PathAhead(context, centre, 0.0, 0.25 * l_bnd, 2)}) {
      for (const Footstep& f : feet) {
        for (const Eigen::Vector2d& c : coarse.centres_m) {
          coarse_feet_x.push_back(NominalFootXY(robot(), f.leg, c.x(), c.y(), 0.0).x());
        }
      }
    }
  }
  double start = -1.0;
  for (double a = 0.8; a < 0.8 + 4.0 * l_bnd && start < 0.0; a += 1e-3) {
    bool clear = true;
    for (double x : coarse_feet_x) clear = clear && (x < a - 1e-3 || x > a + gap + 1e-3);
    if (clear) start = a;
  }
  ASSERT_GT(start, 0.0) << "no place for the gap between the coarse samples";
  regions = {Rect(0, -1.0, -1.0, start, 1.0), Rect(1, start + gap, -1.0, 4.0, 1.0)};

  const PlanStopGap fine = named_gap(options);
  ASSERT_TRUE(fine.found);
  EXPECT_FALSE(fine.blocks);
  EXPECT_NEAR(fine.width_m, gap, 1e-6);
  options.stop_report_step_l_bnd = 4.0;
  const PlanStopGap sparse = named_gap(options);
  EXPECT_TRUE(sparse.examined);
  EXPECT_FALSE(sparse.found);
  options.stop_report_step_l_bnd = 0.25;
  options.stop_report_max_samples = 2;
  const PlanStopGap two = named_gap(options);
  EXPECT_TRUE(two.examined);
  EXPECT_FALSE(two.found);
}

}  // namespace
}  // namespace mfp
