// A corridor cut straight across by a gap wider than the box's step on a world axis
// (d_lim + l_bnd) and narrower than the octagon's, for a URDF robot whose footprint holds
// the octagon: the box model answers no_route at once naming the gap; the octagon model
// crosses it, every step kinematically checked against the derived footprints (not the
// model's rows); the route graph joins exactly what the windows can cross.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "geometry/terrain_description.h"
#include "io/robot_loader.h"
#include "planner/formulation/centre_of_contacts.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/route_guide.h"
#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {
namespace {

// The hexapod at its Table I stance: the footprints' disks about the nominal feet (0.180 m
// less half a cell) hold an octagon wider on the axes than the largest square (0.158 m).
const char* kRobot = "config/robots/hexapod.yaml";

// Two platforms along x, their top faces `region_gap_m` apart once inset by the foot.
std::vector<ConvexRegion> Corridor(const RobotModel& robot, double region_gap_m) {
  const double box_gap = region_gap_m - 2.0 * robot.foot_radius_m;
  TerrainDescription ground;
  TerrainBox near, far;
  near.center_world_m = {-1.0, 0.0, -0.05};
  near.size_m = {2.0, 1.2, 0.1};
  far.center_world_m = {box_gap + 1.0, 0.0, -0.05};
  far.size_m = {2.0, 1.2, 0.1};
  ground.boxes = {near, far};
  return TopFaceRegions(ground, robot.foot_radius_m, robot.max_slope_rad);
}

// Whether every footstep, lifted and set down, lies in its leg's reachable footprint seen
// from one body pose: that of the configuration the step's reach row refers to (the leg's
// previous step, i - n), centre of contacts and reported yaw. "" or the first failure.
std::string OutsideFootprint(const RobotModel& robot, const RobotDerivation& derivation, const Plan& plan) {
  const int n = robot.num_legs();
  const auto& steps = plan.footsteps;
  Eigen::Vector2d mean_nominal = Eigen::Vector2d::Zero();
  for (const LegDerivation& leg : derivation.legs) mean_nominal += leg.nominal_foot_body_m.head<2>() / n;
  auto pos = [&](int j) {
    while (j < 0) j += n;  // before the plan: the start stance
    return Eigen::Vector2d(steps[j].position_world_m.head<2>());
  };
  for (int i = n; i < static_cast<int>(steps.size()); ++i) {
    const int before = i - n;
    const Eigen::Vector2d centre =
        CentreOfContacts<Eigen::Vector2d>(before, n, [&](int k) { return pos(k); });
    const Eigen::Rotation2Dd to_body(-steps[before].yaw_rad);
    const LegDerivation& leg = derivation.legs[steps[i].leg];
    for (const int j : {before, i}) {
      const Eigen::Vector2d body = mean_nominal + to_body * (pos(j) - centre);
      if (!leg.footprint.OccupiedAt(body)) {
        return "step " + std::to_string(j) + " of leg " + std::to_string(steps[i].leg) +
               " is outside its footprint seen from configuration " + std::to_string(before);
      }
    }
  }
  return "";
}

struct Models {
  RobotModel box, octagon;
  RobotDerivation derivation;
  double box_span = 0.0, octagon_span = 0.0;  // one step's reach on a world axis [m]
};

Models Load() {
  Models m;
  const std::string path = std::string(MFP_SOURCE_DIR) + "/" + kRobot;
  m.box = LoadRobot(path, &m.derivation);
  m.octagon = LoadRobot(path, ReachShape::kOctagon);
  m.box_span = m.box.d_lim_m + m.box.l_bnd_m;
  m.octagon_span = m.octagon.d_lim_m + m.octagon.l_bnd_m;
  return m;
}

Plan PlanAcross(const RobotModel& robot, const std::vector<ConvexRegion>& regions, double goal_x_m) {
  PlanRequest request;
  request.start_feet_world_m = NominalStance(robot, regions, -0.5, 0.0, 0.0);
  request.goal_x_m = goal_x_m;
  request.time_limit_s = 120.0;
  const PlannerOptions options;
  const auto solver = MakeRelaxationSolver(options.solvers.backend);
  return PlanFootsteps(robot, regions, request, options, *solver);
}

TEST(ReachShapePlan, AGapWiderThanTheBoxsAxisStepIsCrossedByTheOctagonInsideTheFootprint) {
  const Models m = Load();
  // The footprint must allow it: the octagon reaches farther on an axis than the box.
  ASSERT_GT(m.octagon_span, m.box_span + 0.01) << "box " << m.box_span << " m, octagon " << m.octagon_span << " m";
  const double gap = m.box_span + 0.4 * (m.octagon_span - m.box_span);
  const std::vector<ConvexRegion> regions = Corridor(m.box, gap);
  const double goal_x = gap + 0.5;

  const Plan refused = PlanAcross(m.box, regions, goal_x);
  EXPECT_EQ(refused.status, SolveStatus::kNoRoute) << refused.message;
  EXPECT_NE(refused.message.find("lies across a gap"), std::string::npos) << refused.message;

  const Plan crossed = PlanAcross(m.octagon, regions, goal_x);
  ASSERT_TRUE(HasPlan(crossed.status)) << crossed.message;
  EXPECT_TRUE(crossed.reaches_goal) << crossed.message;
  for (const std::string& v : ValidatePlan(m.octagon, regions, crossed, {goal_x, 0.0, 0.0}, ValidationTolerances{})) {
    ADD_FAILURE() << v;
  }
  EXPECT_EQ(OutsideFootprint(m.octagon, m.derivation, crossed), "");
}

// The footprint shape (each leg's own footprint polygon, turned with the body, about both
// its previous and its own nominal spot): a gap 4 cm wider than the 16-gon's step on the
// axis (a doorway's groove) is refused by the 16-gon and crossed by the footprint, every
// footstep inside its leg's derived footprint seen from the configuration its reach rows
// refer to, and the plan valid by the validator's exact check (the polygon at each step's
// own yaw).
TEST(ReachShapePlan, AGapWiderThanThe16gonsStepIsCrossedByTheFootprintPolygonInsideTheFootprint) {
  const Models m = Load();
  const std::string path = std::string(MFP_SOURCE_DIR) + "/" + kRobot;
  const RobotModel hexadecagon = LoadRobot(path, ReachShape::kHexadecagon);
  const RobotModel footprint = LoadRobot(path, ReachShape::kFootprint);
  ASSERT_EQ(footprint.reach_shape, ReachShape::kFootprint);
  const double span = hexadecagon.d_lim_m + hexadecagon.l_bnd_m;
  const double gap = span + 0.04;
  ASSERT_GT(FootprintStepWidth(footprint), gap + 0.05) << "the footprint polygons' widest step";
  const std::vector<ConvexRegion> regions = Corridor(hexadecagon, gap);
  const double goal_x = gap + 0.5;

  const Plan refused = PlanAcross(hexadecagon, regions, goal_x);
  EXPECT_EQ(refused.status, SolveStatus::kNoRoute) << refused.message;

  const Plan crossed = PlanAcross(footprint, regions, goal_x);
  ASSERT_TRUE(HasPlan(crossed.status)) << crossed.message;
  EXPECT_TRUE(crossed.reaches_goal) << crossed.message;
  for (const std::string& v : ValidatePlan(footprint, regions, crossed, {goal_x, 0.0, 0.0}, ValidationTolerances{})) {
    ADD_FAILURE() << v;
  }
  EXPECT_EQ(OutsideFootprint(footprint, m.derivation, crossed), "");
}

TEST(ReachShapePlan, TheRouteGraphJoinsAGapExactlyWhenOneStepOnTheAxisSpansIt) {
  const Models m = Load();
  for (const RobotModel* robot : {&m.box, &m.octagon}) {
    const double span = robot->d_lim_m + robot->l_bnd_m;
    for (const double share : {0.97, 1.03}) {
      const std::vector<ConvexRegion> regions = Corridor(*robot, share * span);
      const std::vector<Eigen::Vector3d> feet = NominalStance(*robot, regions, -0.5, 0.0, 0.0);
      const RouteGuide guide = PlanRoute(*robot, regions, feet, {share * span + 0.5, 0.0}, 0.0, 0.1, 0.1);
      EXPECT_EQ(guide.connected, share < 1.0) << ReachShapeName(robot->reach_shape) << " at " << share << ": "
                                              << guide.broken;
    }
  }
}

}  // namespace
}  // namespace mfp
