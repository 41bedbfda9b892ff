// Route-following proposals (planner/planning/internal/route_proposals.h) on a field of small
// cells built by hand: the proposals are integer assignments of the window's MIQP, at
// least one is a plan, and the best one walks the body along the route at half of d_lim
// per configuration or more.
#include "planner/planning/internal/route_proposals.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/robot_loader.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/warm_start.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {
namespace {

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1, double z = 0.0) {
  return MakeRegionFromPolygon(id, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, 0.0);
}

class RouteProposalsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = LoadRobot(std::string(MFP_SOURCE_DIR) + "/config/robots/littledog.yaml");
    // A start pad, then cells of 6 cm with 2 cm gaps and heights 0-2 cm along +x.
    regions_.push_back(Rect(0, -0.3, -0.3, 0.3, 0.3));
    int id = 1;
    for (int i = 0; i < 20; ++i) {
      for (int j = -4; j < 4; ++j) {
        const double x0 = 0.32 + 0.08 * i, y0 = 0.08 * j + 0.01;
        regions_.push_back(Rect(id++, x0, y0, x0 + 0.06, y0 + 0.06, 0.01 * ((i * 7 + j * 3) % 3)));
      }
    }
    request_.start_yaw_rad = 0.0;
    for (int leg = 0; leg < robot_.num_legs(); ++leg) {
      const Eigen::Vector2d xy = NominalFootXY(robot_, leg, 0.0, 0.0, 0.0);
      request_.start_feet_world_m.emplace_back(xy.x(), xy.y(), 0.0);
    }
    request_.goal_x_m = 1.9;
    request_.goal_y_m = 0.0;
    guide_.connected = true;
    guide_.route = {{0.0, 0.0}, {1.9, 0.0}};
    guide_.length_m = 1.9;
  }
  RobotModel robot_;
  std::vector<ConvexRegion> regions_;
  PlanRequest request_;
  RouteGuide guide_;
};

TEST_F(RouteProposalsTest, TheBestProposalWalksTheRoute) {
  const PlannerOptions options;
  // A window that starts with the front feet at the field's edge: every step lands on a cell.
  PlanRequest request = request_;
  for (Eigen::Vector3d& f : request.start_feet_world_m) f.x() += 0.15;
  const MiqpFormulation formulation(FirstWindowProblem(robot_, regions_, request, options), options.formulation);
  const std::vector<Eigen::VectorXd> proposals = RouteProposals(formulation, guide_, 0.15);
  ASSERT_FALSE(proposals.empty());
  for (const Eigen::VectorXd& x : proposals) {
    ASSERT_EQ(x.size(), formulation.miqp().num_variables());
    for (int i = formulation.num_legs(); i < formulation.num_steps(); ++i) {
      int chosen = 0;
      for (int h : formulation.vars().region[static_cast<size_t>(i)]) chosen += h >= 0 && x(h) > 0.5 ? 1 : 0;
      EXPECT_EQ(chosen, 1) << "step " << i;
    }
  }
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  const std::optional<Eigen::VectorXd> best = SolveWarmStart(formulation, proposals, *solver, Deadline::After(10.0), 1e-5);
  ASSERT_TRUE(best.has_value()) << "no proposal is a plan";
  // The last configuration's feet: their centre has moved along +x.
  const int n = formulation.num_legs();
  const int configurations = formulation.num_configurations() - 1;
  double centre_x = 0.0;
  for (int i = formulation.num_steps() - n; i < formulation.num_steps(); ++i) {
    centre_x += (*best)(formulation.vars().x[static_cast<size_t>(i)]) / n;
  }
  EXPECT_GT(centre_x - 0.15, 0.5 * robot_.d_lim_m * configurations);
}

TEST_F(RouteProposalsTest, AStanceOffTheRouteWalksBackToIt) {
  // The stance stands 0.15 m beside the route (more than d_lim + l_bnd): proposals that put
  // the body on the route at once move every foot farther than a step reaches; walking
  // back at the proposal's speed, one is a plan (go1_rough_turn_109 swerved round the
  // field's corner and stalled with no proposal that fitted).
  const PlannerOptions options;
  PlanRequest request = request_;
  for (Eigen::Vector3d& f : request.start_feet_world_m) f.x() += 0.15;
  RouteGuide beside = guide_;
  beside.route = {{0.0, -0.15}, {1.9, -0.15}};
  ASSERT_GT(0.15, robot_.d_lim_m + robot_.l_bnd_m);
  const MiqpFormulation formulation(FirstWindowProblem(robot_, regions_, request, options), options.formulation);
  const std::vector<Eigen::VectorXd> proposals = RouteProposals(formulation, beside, 0.15);
  ASSERT_FALSE(proposals.empty());
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  const std::optional<Eigen::VectorXd> best = SolveWarmStart(formulation, proposals, *solver, Deadline::After(10.0), 1e-5);
  ASSERT_TRUE(best.has_value()) << "no proposal is a plan";
  // The last configuration's centre has come closer to the route.
  const int n = formulation.num_legs();
  double centre_y = 0.0;
  for (int i = formulation.num_steps() - n; i < formulation.num_steps(); ++i) {
    centre_y += (*best)(formulation.vars().y[static_cast<size_t>(i)]) / n;
  }
  EXPECT_LT(centre_y, -0.02);
}

TEST_F(RouteProposalsTest, NoRouteNoProposals) {
  const PlannerOptions options;
  const MiqpFormulation formulation(FirstWindowProblem(robot_, regions_, request_, options), options.formulation);
  EXPECT_TRUE(RouteProposals(formulation, RouteGuide{}, 0.0).empty());
}

}  // namespace
}  // namespace mfp
