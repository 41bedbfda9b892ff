// Body regions in the windows (issue 29): free regions grown about a seed shape
// (geometry/free_region_2d.h), the MIQP's body rows (planner/formulation/body_region_faces.h)
// on a hand-built window, and the hexapod's doorway, whose door is a few centimetres wider
// than the body a side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "bench/course_checker.h"
#include "bench/course_generator.h"
#include "geometry/free_region_2d.h"
#include "io/robot_loader.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/robot/body_clearance.h"
#include "planner/search/branch_and_bound.h"
#include "tests/plan_course.h"

namespace mfp {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

std::string RobotPath(const std::string& name) { return std::string(MFP_SOURCE_DIR) + "/config/robots/" + name + ".yaml"; }

Polygon Box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1) {
  return MakeRegionFromPolygon(id, {{x0, y0, 0.0}, {x1, y0, 0.0}, {x1, y1, 0.0}, {x0, y1, 0.0}}, 0.0);
}

TEST(FreeRegion, HoldsItsSeedAndMeetsNoObstacleAmongRandomBoxes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-2.0, 2.0), size(0.05, 0.6), turn(-M_PI, M_PI);
  int grown = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Polygon> obstacles;
    for (int k = 0; k < 8; ++k) {
      const double cx = at(rng), cy = at(rng), hx = size(rng), hy = size(rng), yaw = turn(rng);
      Polygon p;
      for (const Eigen::Vector2d& c : Box(-hx, -hy, hx, hy)) p.push_back(Eigen::Vector2d(cx, cy) + Eigen::Rotation2Dd(yaw) * c);
      obstacles.push_back(p);
    }
    Polygon seed;
    const double yaw = turn(rng);
    for (const Eigen::Vector2d& c : Box(-0.2, -0.1, 0.2, 0.1)) seed.push_back(Eigen::Rotation2Dd(yaw) * c);
    const std::optional<FreeRegion2d> region = GrowFreeRegion(seed, obstacles, {-3, -3}, {3, 3});
    double seed_overlap = 0.0;
    for (const Polygon& o : obstacles) seed_overlap = std::max(seed_overlap, ConvexOverlapArea(seed, o));
    if (!region) {
      EXPECT_GT(seed_overlap, 0.0) << "trial " << trial << ": a clear seed got no region";
      continue;
    }
    ++grown;
    EXPECT_LE(RegionExcess(*region, seed), 1e-12);
    for (const Polygon& o : obstacles) EXPECT_LE(ConvexOverlapArea(region->polygon, o), 1e-9) << "trial " << trial;
    // The polygon is the region: its vertices meet the rows.
    EXPECT_LE(RegionExcess(*region, region->polygon), 1e-9);
  }
  EXPECT_GT(grown, 20);
}

TEST(FreeRegion, AmongTheNearObstaclesItIsTheRegionAmongAllWhenTheNearBoundsSaySo) {
  // Unit squares on a lattice (the convex cover's obstacles) about a rectangle seed: grown
  // among the squares within `near` of the seed only, the region is the one grown among
  // all whenever the bounds reported at gap `near` lie strictly inside the near window.
  std::mt19937 rng(5);
  std::bernoulli_distribution blocked(0.12);
  int certified = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int size = 40, near = std::uniform_int_distribution<int>(2, 8)(rng);
    const int x0 = std::uniform_int_distribution<int>(10, 26)(rng), y0 = std::uniform_int_distribution<int>(10, 26)(rng);
    const int w = std::uniform_int_distribution<int>(1, 4)(rng), h = std::uniform_int_distribution<int>(1, 4)(rng);
    std::vector<Polygon> all, near_ones;
    for (int r = 0; r < size; ++r) {
      for (int c = 0; c < size; ++c) {
        const bool in_seed = c >= x0 && c < x0 + w && r >= y0 && r < y0 + h;
        if (in_seed || !blocked(rng)) continue;
        all.push_back(Box(c, r, c + 1, r + 1));
        if (c >= x0 - near && c < x0 + w + near && r >= y0 - near && r < y0 + h + near) near_ones.push_back(all.back());
      }
    }
    const Polygon seed = Box(x0, y0, x0 + w, y0 + h);
    const Eigen::Vector2d lo(0, 0), hi(size, size);
    Eigen::Vector2d near_lo, near_hi;
    const std::optional<FreeRegion2d> from_near = GrowFreeRegionNear(seed, near_ones, lo, hi, near, &near_lo, &near_hi);
    const std::optional<FreeRegion2d> from_all = GrowFreeRegion(seed, all, lo, hi);
    ASSERT_TRUE(from_near && from_all);
    if (!(near_lo.x() > x0 - near && near_lo.y() > y0 - near && near_hi.x() < x0 + w + near && near_hi.y() < y0 + h + near)) {
      continue;
    }
    ++certified;
    ASSERT_EQ(from_near->polygon.size(), from_all->polygon.size()) << "trial " << trial;
    for (size_t k = 0; k < from_all->polygon.size(); ++k) EXPECT_EQ(from_near->polygon[k], from_all->polygon[k]);
    EXPECT_EQ(from_near->A, from_all->A);
    EXPECT_EQ(from_near->b, from_all->b);
  }
  EXPECT_GT(certified, 50);
}

TEST(FreeRegion, AmongTheFirstObstaclesOfAWorkSpaceItIsTheRegionAmongThoseAlone) {
  // The convex cover's work space holds more polygons than one growth uses (left over from
  // an earlier, larger one): grown among the first `count`, the region is the one grown
  // among a vector of those alone, whatever follows them.
  std::mt19937 rng(9);
  std::bernoulli_distribution blocked(0.15);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<Polygon> used, space;
    for (int r = 0; r < 30; ++r) {
      for (int c = 0; c < 30; ++c) {
        if ((c >= 12 && c < 15 && r >= 12 && r < 14) || !blocked(rng)) continue;
        used.push_back(Box(c, r, c + 1, r + 1));
      }
    }
    space = used;
    for (int k = 0; k < 20; ++k) space.push_back(Box(12 + k % 3, 12, 13 + k % 3, 13));  // over the seed: would refuse it
    const Polygon seed = Box(12, 12, 15, 14);
    const Eigen::Vector2d lo(0, 0), hi(30, 30);
    Eigen::Vector2d lo_a, hi_a, lo_b, hi_b;
    const std::optional<FreeRegion2d> alone = GrowFreeRegionNear(seed, used, lo, hi, 4.0, &lo_a, &hi_a);
    const std::optional<FreeRegion2d> first = GrowFreeRegionNear(seed, space.data(), used.size(), lo, hi, 4.0, &lo_b, &hi_b);
    ASSERT_TRUE(alone && first);
    EXPECT_EQ(first->polygon, alone->polygon);
    EXPECT_EQ(first->A, alone->A);
    EXPECT_EQ(first->b, alone->b);
    EXPECT_EQ(lo_b, lo_a);
    EXPECT_EQ(hi_b, hi_a);
    EXPECT_FALSE(GrowFreeRegionNear(seed, space.data(), space.size(), lo, hi, 4.0, &lo_b, &hi_b));
  }
}

TEST(FreeRegion, ABodyInADoorGetsTheDoorsStripThroughTheWall) {
  // A wall along y at x in [1, 1.1] with a door y in [-0.2, 0.2]; the seed stands in it.
  const std::vector<Polygon> walls = {Box(1.0, 0.2, 1.1, 2.0), Box(1.0, -2.0, 1.1, -0.2)};
  const std::optional<FreeRegion2d> region = GrowFreeRegion(Box(0.9, -0.15, 1.2, 0.15), walls, {-1, -2}, {3, 2});
  ASSERT_TRUE(region);
  // Before and after the door, the strip is the door's width: the body can enter it only
  // turned (here: facing x) and reaches a metre on either side.
  EXPECT_LE(RegionExcess(*region, {{0.0, 0.19}, {0.0, -0.19}, {2.0, 0.19}, {2.0, -0.19}}), 0.0);
  EXPECT_GT(RegionExcess(*region, {{0.0, 0.25}}), 0.0);
}

// A hand-built window: LittleDog at the nominal stance, a wall beside it (its near face a
// few centimetres off the body's left side) and a goal beyond the wall's face. The body
// region grown about the start keeps every configuration's true body box off the wall;
// without the body rows the plan walks the body into it.
class BodyRowsTest : public ::testing::Test {
 protected:
  BodyRowsTest() : robot_(LoadRobot(RobotPath("littledog"))) {
    problem_.robot = &robot_;
    problem_.regions = {Rect(0, -1.0, -1.0, 2.0, 1.0)};
    const int n = robot_.num_legs();
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d f = NominalFootXY(robot_, robot_.gait[i], 0.0, 0.0, 0.0);
      problem_.start_feet_world_m.push_back({f.x(), f.y(), 0.0});
    }
    wall_face_y_ = robot_.body.max_m.y() + 0.03;
    problem_.goal_x_m = 0.3;
    problem_.goal_y_m = wall_face_y_ + 0.2;
    problem_.num_new_steps = 2 * n;
    wall_ = Box(-0.5, wall_face_y_, 1.0, wall_face_y_ + 0.1);
    problem_.body_regions = {*GrowFreeRegion(BodyFootprint(robot_.body, 0, 0, 0), {wall_}, {-1.5, -1.5}, {2.5, 1.5})};
  }

  // The largest share of the body box the wall covers over the plan's configurations.
  double WorstWallShare(bool body_rows) const {
    FormulationOptions options = PlannerOptions().formulation;
    options.body_regions = body_rows;
    const MiqpFormulation formulation(problem_, options);
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(PlannerOptions().solvers.backend, 1);
    BranchAndBoundOptions bnb = PlannerOptions().branch_and_bound;
    bnb.time_limit_s = 20.0;
    const RoundingHeuristic rounding = [&](const Eigen::VectorXd& x) { return formulation.RoundAlongPlan(x); };
    const BranchAndBoundResult r = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb, rounding);
    EXPECT_GT(r.x.size(), 0);
    if (r.x.size() == 0) return 1.0;
    const std::vector<Footstep> steps = formulation.ExtractFootsteps(r.x);
    const BodyObstacle wall{wall_, 0.0, 1.0};
    const int n = robot_.num_legs();
    double worst = 0.0;
    for (size_t i = n; i < steps.size(); ++i) {
      std::vector<Eigen::Vector3d> stance;
      for (size_t k = i + 1 - n; k <= i; ++k) stance.push_back(steps[k].position_world_m);
      const Eigen::Vector2d c = StanceCentreXY(stance);
      worst = std::max(worst, BodyOverlapShare(robot_.body, {wall}, c.x(), c.y(), steps[i].yaw_rad, 0.0));
    }
    return worst;
  }

  RobotModel robot_;
  FootstepProblem problem_;
  double wall_face_y_ = 0.0;
  Polygon wall_;
};

TEST_F(BodyRowsTest, TheBodyRowsKeepEveryConfigurationsBodyOffTheWall) {
  ASSERT_TRUE(robot_.body.known());
  EXPECT_GT(WorstWallShare(false), 0.0) << "the goal should pull the body into the wall without its rows";
  EXPECT_EQ(WorstWallShare(true), 0.0);
}

TEST_F(BodyRowsTest, WithoutBodyRegionsTheMiqpIsUnchanged) {
  FootstepProblem bare = problem_;
  bare.body_regions.clear();
  FormulationOptions options = PlannerOptions().formulation;
  options.body_regions = true;
  const MiqpFormulation with_none(bare, options);
  FormulationOptions off = options;
  off.body_regions = false;
  const MiqpFormulation switched_off(problem_, off);
  EXPECT_EQ(with_none.miqp().num_variables(), switched_off.miqp().num_variables());
  EXPECT_EQ(with_none.miqp().num_rows(), switched_off.miqp().num_rows());
  const MiqpFormulation with_rows(problem_, options);
  EXPECT_GT(with_rows.miqp().num_rows(), with_none.miqp().num_rows());
}

// The hexapod's nearly square body has 1.5-2.7 cm a side in this door: its windows must
// turn the body to the door's heading before the wall. With the defaults (body regions
// off) the stance route and the windows' body check do it; this keeps that course green.
// It does not tell the body rows' effect apart: BodyRowsTest above does.
TEST(BodyRegionCourses, TheHexapodTurnsThroughATightDoorBodyClear) {
  const RobotModel robot = LoadRobot(RobotPath("hexapod"));
  const Course course = GenerateCourse(robot, RobotPath("hexapod"), CourseKind::kDoorway, 5);
  const CourseOutcome out = PlanCourse(course, robot, 120.0);
  EXPECT_TRUE(out.verdict.valid) << out.verdict.cause << " " << out.plan.message;
  EXPECT_TRUE(out.verdict.body_clear) << out.verdict.body_overlap_share;
  EXPECT_TRUE(out.verdict.reaches_goal) << ToString(out.plan.status) << " " << out.plan.message;
}

}  // namespace
}  // namespace mfp
