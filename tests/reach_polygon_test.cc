// The step polygon of the two reach shapes, the bridge test the route graph joins regions
// by, and the derived octagon's soundness: its corners, turned by any body yaw, lie in
// every leg's reachable footprint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "planner/robot/derivation_budget.h"
#include "planner/robot/reach_polygon.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/urdf_reader.h"
#include "test_robots.h"

namespace mfp {
namespace {

std::vector<Eigen::Vector2d> Square(double x, double y, double half) {
  return {{x - half, y - half}, {x + half, y - half}, {x + half, y + half}, {x - half, y + half}};
}

TEST(ReachPolygon, TheStepPolygonReachesDLimPlusLBndOnAnAxisAndMoreOnADiagonal) {
  RobotModel robot = SquareQuadruped(0.2, 0.1);
  const std::vector<Eigen::Vector2d> box = StepPolygon(robot);
  EXPECT_NEAR(StepReachAlong(box, {1, 0}), 0.3, 1e-12);
  EXPECT_NEAR(StepReachAlong(box, {0, -1}), 0.3, 1e-12);
  EXPECT_NEAR(StepReachAlong(box, {1, 1}), std::sqrt(2.0) * 0.3, 1e-12);
  robot.reach_shape = ReachShape::kOctagon;
  const std::vector<Eigen::Vector2d> octagon = StepPolygon(robot);
  EXPECT_EQ(octagon.size(), 8u);
  EXPECT_NEAR(StepReachAlong(octagon, {-1, 0}), 0.3, 1e-12);
  // The octagon's apothem on the diagonal plus the reference box's corner.
  EXPECT_NEAR(StepReachAlong(octagon, {1, 1}), 0.2 + std::sqrt(2.0) * 0.1, 1e-12);
  for (const Eigen::Vector2d& v : ReachPolygon(ReachShape::kOctagon, 0.2)) {
    EXPECT_NEAR(v.norm(), 0.2 / std::cos(M_PI / 8.0), 1e-12);
  }
  // The 16-gon: the box's edges lie along four of its faces, so the sum keeps 16 corners.
  robot.reach_shape = ReachShape::kHexadecagon;
  const std::vector<Eigen::Vector2d> sixteen = StepPolygon(robot);
  EXPECT_EQ(sixteen.size(), 16u);
  EXPECT_NEAR(StepReachAlong(sixteen, {0, 1}), 0.3, 1e-12);
  EXPECT_NEAR(StepReachAlong(sixteen, {1, 1}), 0.2 + std::sqrt(2.0) * 0.1, 1e-12);
  const std::vector<Eigen::Vector2d> corners = ReachPolygon(ReachShape::kHexadecagon, 0.2);
  ASSERT_EQ(corners.size(), 16u);
  for (size_t k = 0; k < corners.size(); ++k) {
    EXPECT_NEAR(corners[k].norm(), 0.2 / std::cos(M_PI / 16.0), 1e-12);
    // Counter-clockwise, pi/8 apart, the first just below the x axis.
    const double angle = std::atan2(corners[k].y(), corners[k].x());
    EXPECT_NEAR(std::remainder(angle - (2.0 * k - 1.0) * M_PI / 16.0, 2.0 * M_PI), 0.0, 1e-12) << k;
  }
}

TEST(ReachPolygon, StepsToBridgeIsTheGapOverTheStepsReachAcrossIt) {
  const RobotModel robot = SquareQuadruped(0.2, 0.1);
  const std::vector<Eigen::Vector2d> step = StepPolygon(robot);
  // Along x: a 0.27 m gap bridges, a 0.33 m one does not.
  EXPECT_NEAR(StepsToBridge(Square(0, 0, 0.5), Square(1.27, 0, 0.5), step), 0.9, 1e-9);
  EXPECT_NEAR(StepsToBridge(Square(0, 0, 0.5), Square(1.33, 0.2, 0.5), step), 1.1, 1e-9);
  // Overlapping regions: no step needed.
  EXPECT_EQ(StepsToBridge(Square(0, 0, 0.5), Square(0.8, 0, 0.5), step), 0.0);
  // Corner to corner on the diagonal the box reaches sqrt(2) times farther.
  const double d = 1.0 + 0.35;  // corners 0.35 * sqrt(2) = 0.49 m apart
  EXPECT_NEAR(StepsToBridge(Square(0, 0, 0.5), Square(d, d, 0.5), step), 0.35 / 0.3, 1e-9);
  EXPECT_NEAR(StepsToBridge(Square(0, 0, 0.5), Square(1.25, 1.25, 0.5), step), 0.25 / 0.3, 1e-9);
}

// Every repository URDF: the derived octagon's corners about each leg's nominal foot, at
// body yaws every 5 degrees, lie in that leg's footprint, with the reference box's corners.
TEST(ReachPolygon, TheDerivedOctagonLiesInEveryFootprintAtEveryBodyYaw) {
  for (const char* file : {"config/robots/littledog.urdf", "config/robots/hexapod.urdf",
                           "tests/data/robots/octopod.urdf"}) {
    RobotDescription description = ReadUrdfRobot(std::string(MFP_SOURCE_DIR) + "/" + file);
    DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &description);
    options.reach_shape = ReachShape::kOctagon;
    const RobotDerivation derivation = DeriveRobot(description, options);
    const RobotModel& robot = derivation.model;
    ASSERT_EQ(robot.reach_shape, ReachShape::kOctagon) << file;
    ASSERT_EQ(derivation.legs.size(), robot.legs.size()) << file;
    double smallest_disk = 1e9;
    for (const LegDerivation& leg : derivation.legs) smallest_disk = std::min(smallest_disk, leg.disk_radius_m);
    EXPECT_LT(robot.d_lim_m / std::cos(M_PI / 8.0), smallest_disk) << file;
    for (size_t k = 0; k < derivation.legs.size(); ++k) {
      const LegDerivation& leg = derivation.legs[k];
      for (int degrees = 0; degrees < 360; degrees += 5) {
        const Eigen::Rotation2Dd turn(degrees * M_PI / 180.0);
        for (const Eigen::Vector2d& v : ReachPolygon(ReachShape::kOctagon, robot.d_lim_m)) {
          EXPECT_TRUE(leg.footprint.OccupiedAt(leg.nominal_foot_body_m.head<2>() + turn * v))
              << file << " leg " << k << " at " << degrees << " deg";
        }
        for (const Eigen::Vector2d& v : ReachPolygon(ReachShape::kBox, robot.l_bnd_m)) {
          EXPECT_TRUE(leg.footprint.OccupiedAt(leg.nominal_foot_body_m.head<2>() + turn * v))
              << file << " leg " << k << " reference box at " << degrees << " deg";
        }
      }
    }
  }
}

// MaxMovesXY bounds a footprint leg's later move by FootprintDiameter: both feet lie in the
// leg's polygon about the same nominal spot, turned by the same yaw, so a move on an axis
// is at most the polygon's width across that axis. The bound must hold every such move (the
// trimming big-M and region pruning rely on it) and cut none: the widest width of the
// polygon's points (a fine grid of them, found by its faces alone) over 72 directions is the
// diameter, to within the grid's step.
TEST(ReachPolygon, AFootprintLegsMoveOnAnAxisReachesItsDiameterAndNoFarther) {
  RobotDescription description =
      ReadUrdfRobot(std::string(MFP_SOURCE_DIR) + "/tests/data/robots/octopod.urdf");
  DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &description);
  options.reach_shape = ReachShape::kFootprint;
  const RobotModel robot = DeriveRobot(description, options).model;
  ASSERT_EQ(robot.reach_shape, ReachShape::kFootprint);
  for (size_t k = 0; k < robot.legs.size(); ++k) {
    const LegModel& leg = robot.legs[k];
    double reach = 0.0;
    for (const ReachFace& f : leg.footprint_faces) reach = std::max(reach, f.offset_m);
    const int cells = 300;
    const double step = 4.0 * reach / cells;  // the grid spans [-2 reach, 2 reach]^2
    std::vector<Eigen::Vector2d> points;
    for (int a = 0; a <= cells; ++a) {
      for (int b = 0; b <= cells; ++b) {
        const Eigen::Vector2d p(-2.0 * reach + a * step, -2.0 * reach + b * step);
        bool inside = true;
        for (const ReachFace& f : leg.footprint_faces) inside = inside && f.normal.dot(p) <= f.offset_m;
        if (inside) points.push_back(p);
      }
    }
    ASSERT_GT(points.size(), 100u) << "leg " << k;
    double widest = 0.0;
    for (int degrees = 0; degrees < 180; degrees += 2) {
      const Eigen::Vector2d u(std::cos(degrees * M_PI / 180.0), std::sin(degrees * M_PI / 180.0));
      double lo = 1e9, hi = -1e9;
      for (const Eigen::Vector2d& p : points) lo = std::min(lo, u.dot(p)), hi = std::max(hi, u.dot(p));
      widest = std::max(widest, hi - lo);
    }
    const double diameter = FootprintDiameter(leg);
    EXPECT_LE(widest, diameter + 1e-12) << "leg " << k;
    EXPECT_GE(widest, diameter - 3.0 * step) << "leg " << k;
  }
}
}  // namespace
}  // namespace mfp
