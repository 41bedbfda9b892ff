// Progress, not budget (planner/planning/internal/plan_progress.h, HorizonState::NoteProgress,
// HorizonPolicy::Stalled): a plan whose way left stops shrinking ends partial at its best
// point instead of spending its step budget marking time.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "io/robot_loader.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/horizon_policy.h"
#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/planning/internal/plan_progress.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {
namespace {

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1) {
  return MakeRegionFromPolygon(id, {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, 0.0);
}

RobotModel LittleDog() { return LoadRobot(std::string(MFP_SOURCE_DIR) + "/config/robots/littledog.yaml"); }

PlanRequest RequestFrom(const RobotModel& robot, const std::vector<ConvexRegion>& regions, double goal_x_m) {
  PlanRequest request;
  request.start_feet_world_m = NominalStance(robot, regions, 0.0, 0.0, 0.0);
  request.goal_x_m = goal_x_m;
  request.time_limit_s = 60.0;
  return request;
}

TEST(RouteLeft, ArcLengthLeftAndTurnsOnTheSpotCount) {
  RouteGuide guide;
  guide.route = {{0, 0}, {1, 0}, {1, 0}, {1, 2}};
  EXPECT_NEAR(RouteLeft(guide, {0.25, 0.1}, 0.0, 0.0), 2.75, 1e-12);
  EXPECT_NEAR(RouteLeft(guide, {1.1, 1.5}, 0.0, 0.0), 0.5, 1e-12);
  // With yaws, the quarter turn at (1, 0) is 0.5 m of route at 1/pi m per radian.
  guide.yaws_rad = {0.0, 0.0, M_PI / 2, M_PI / 2};
  const double rho = 1.0 / M_PI;
  EXPECT_NEAR(RouteLeft(guide, {1.0, 0.0}, 0.0, rho), 2.5, 1e-12);
  EXPECT_NEAR(RouteLeft(guide, {1.0, 0.0}, M_PI / 4, rho), 2.25, 1e-12);
  EXPECT_NEAR(RouteLeft(guide, {1.0, 0.0}, M_PI / 2, rho), 2.0, 1e-12);
}

// A beam one foot wide between two floors: every foot's region graph crosses it and
// stances whose legs' boxes are widened to sqrt(2) l_bnd stand over it, so the route
// goes straight on; but no stance of LittleDog has every foot within l_bnd of its nominal
// spot on the beam. The windows walk to the beam and can go no farther.
class BeamDeadEnd : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = LittleDog();
    regions_ = {Rect(0, -0.4, -0.3, 0.3, 0.3), Rect(1, 0.3, -0.01, 1.0, 0.01), Rect(2, 1.0, -0.3, 1.6, 0.3)};
    request_ = RequestFrom(robot_, regions_, 1.3);
  }
  RobotModel robot_;
  std::vector<ConvexRegion> regions_;
  PlanRequest request_;
  PlannerOptions options_;
};

TEST_F(BeamDeadEnd, APlanThatStopsMakingProgressEndsWithinTwoWindowsOfItsBestPoint) {
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options_.solvers.backend, 1);
  const Plan plan = PlanFootsteps(robot_, regions_, request_, options_, solvers.workers());
  ASSERT_EQ(plan.status, SolveStatus::kPartial) << plan.message;
  EXPECT_FALSE(plan.reaches_goal);

  // The way left of every stance of the plan (after each step), as the planner measures it.
  std::vector<RelaxationSolver*> none;
  PlanContext context(robot_, regions_, request_, options_, none);
  ASSERT_FALSE(SetUpPlan(&context).has_value());
  ASSERT_TRUE(context.guided);
  const size_t n = static_cast<size_t>(robot_.num_legs());
  double best = std::numeric_limits<double>::infinity();
  size_t best_steps = 0;
  for (size_t size = n; size <= plan.footsteps.size(); ++size) {
    const double left = RemainingWay(context, std::vector<Footstep>(plan.footsteps.begin(), plan.footsteps.begin() + size));
    if (left < best - 1e-9) {
      best = left;
      best_steps = size;
    }
  }
  const size_t window = static_cast<size_t>(context.window_steps);
  EXPECT_LE(plan.footsteps.size() - best_steps, 2 * window) << plan.footsteps.size() << " steps, best after " << best_steps;
  // It stopped on its progress, long before its step budget.
  EXPECT_LT(plan.footsteps.size() - n, static_cast<size_t>(context.max_steps) / 4) << plan.message;
  EXPECT_LE(plan.windows, 40) << plan.message;
}

// A stopped plan says what keeps it from the goal in the goal test's terms: its farthest final
// foot from its goal spot and its yaw, each beside its tolerance, and one of them is beyond it.
TEST_F(BeamDeadEnd, APartialPlanNamesItsFarthestFootAndYawAgainstTheGoalTolerances) {
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options_.solvers.backend, 1);
  const Plan plan = PlanFootsteps(robot_, regions_, request_, options_, solvers.workers());
  ASSERT_EQ(plan.status, SolveStatus::kPartial) << plan.message;
  const std::string& m = plan.message;
  const size_t foot = m.find("farthest foot ");
  const size_t yaw = m.find("; yaw ");
  ASSERT_NE(foot, std::string::npos) << m;
  ASSERT_NE(yaw, std::string::npos) << m;
  EXPECT_NE(m.find("goal_tolerance " + std::to_string(options_.goal_tolerance_m).substr(0, 4)), std::string::npos) << m;
  const double foot_m = std::stod(m.substr(foot + 14));
  const double yaw_rad = std::stod(m.substr(yaw + 6));
  EXPECT_TRUE(foot_m > options_.goal_tolerance_m || yaw_rad > options_.goal_yaw_tolerance_rad) << m;
}

}  // namespace
}  // namespace mfp
