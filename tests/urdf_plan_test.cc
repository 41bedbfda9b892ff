// Planning from a URDF alone (defaults for everything a URDF cannot say) for robots of
// 4, 6 and 8 legs, and for a robot whose feet are collision spheres with no foot links.
#include <gtest/gtest.h>

#include "geometry/terrain_description.h"
#include "io/robot_loader.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {
namespace {

struct Case {
  std::string urdf;
  int legs;
};

class UrdfPlan : public ::testing::TestWithParam<Case> {};

TEST_P(UrdfPlan, WalksAndTurnsOnFlatGround) {
  const RobotModel robot = LoadRobot(std::string(MFP_SOURCE_DIR) + "/" + GetParam().urdf);
  ASSERT_EQ(robot.num_legs(), GetParam().legs);
  TerrainDescription ground;
  TerrainBox box;
  box.center_world_m = {0.5, 0.0, -0.05};
  box.size_m = {3.0, 2.0, 0.1};
  ground.boxes = {box};
  const std::vector<ConvexRegion> regions = TopFaceRegions(ground, robot.foot_radius_m, robot.max_slope_rad);
  PlanRequest request;
  request.start_feet_world_m = NominalStance(robot, regions, 0.0, 0.0, 0.0);
  request.goal_x_m = 0.4;
  request.goal_yaw_rad = 0.3;
  request.time_limit_s = 120.0;
  const PlannerOptions options;
  const auto solver = MakeRelaxationSolver(options.solvers.backend);
  const Plan plan = PlanFootsteps(robot, regions, request, options, *solver);
  ASSERT_TRUE(HasPlan(plan.status)) << plan.message;
  EXPECT_TRUE(plan.reaches_goal) << plan.message;
  EXPECT_TRUE(plan.message.empty()) << plan.message;  // no window kept the MIQP's plan
  const ValidationTolerances tol;  // exact trigonometry
  for (const std::string& v : ValidatePlan(robot, regions, plan, {0.4, 0.0, 0.3}, tol)) ADD_FAILURE() << v;
}

INSTANTIATE_TEST_SUITE_P(Robots, UrdfPlan,
                         ::testing::Values(Case{"config/robots/littledog.urdf", 4}, Case{"config/robots/hexapod.urdf", 6},
                                           Case{"tests/data/robots/octopod.urdf", 8},
                                           Case{"tests/data/robots/sphere_quad.urdf", 4}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.urdf.substr(info.param.urdf.find_last_of('/') + 1);
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace mfp
