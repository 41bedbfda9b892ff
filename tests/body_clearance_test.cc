// Body clearance: the body box derived from the URDF (planner/robot/body_clearance.h),
// the stance route that keeps it clear (planner/planning/internal/stance_route.h), and plans on
// the body courses (a door that needs a turn, a dead-end pocket) judged by the checker
// against the true boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include "base/check.h"
#include "bench/course_checker.h"
#include "bench/course_generator.h"
#include "io/body_obstacles.h"
#include "io/robot_json.h"
#include "io/robot_loader.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/planning/internal/stance_route.h"
#include "planner/planning/internal/window_body_check.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/robot/body_clearance.h"
#include "planner/robot/body_obstacle_index.h"
#include "tests/plan_course.h"

namespace mfp {
namespace {

std::string RobotPath(const std::string& name) { return std::string(MFP_SOURCE_DIR) + "/config/robots/" + name + ".yaml"; }

TEST(BodyBox, DerivedFromTheUrdfAndShown) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  ASSERT_TRUE(robot.body.known());
  EXPECT_GT(robot.body.length_m(), robot.body.width_m());
  EXPECT_GT(robot.body.bottom_m, 0.0);
  EXPECT_LT(robot.body.bottom_m, robot.stance_height_m);
  const nlohmann::json j = RobotToJson(robot);
  EXPECT_TRUE(j["body_box"]["known"].get<bool>());
  EXPECT_DOUBLE_EQ(j["body_box"]["length"].get<double>(), robot.body.length_m());
}

TEST(BodyBox, OverriddenInTheRobotYaml) {
  const std::string path = ::testing::TempDir() + "/body_box_robot.yaml";
  std::ofstream(path) << "urdf: " << MFP_SOURCE_DIR << "/config/robots/littledog.urdf\n"
                      << "stance_height: 0.124\nbody_box: {min: [-0.2, -0.1], max: [0.25, 0.1], bottom: 0.05, top: 0.12}\n";
  const RobotModel robot = LoadRobot(path);
  EXPECT_DOUBLE_EQ(robot.body.min_m.x(), -0.2);
  EXPECT_DOUBLE_EQ(robot.body.max_m.x(), 0.25);
  EXPECT_DOUBLE_EQ(robot.body.bottom_m, 0.05);
  std::ofstream(path) << "urdf: " << MFP_SOURCE_DIR << "/config/robots/littledog.urdf\n"
                      << "stance_height: 0.124\nbody_box: {min: [0.3, -0.1], max: [0.25, 0.1]}\n";
  EXPECT_THROW(LoadRobot(path), InputError);
  std::remove(path.c_str());
}

TEST(BodyClearance, OverlapOfConvexPolygons) {
  const std::vector<Eigen::Vector2d> a = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const std::vector<Eigen::Vector2d> b = {{1, 0.5}, {3, 0.5}, {3, 2}, {1, 2}};
  EXPECT_NEAR(ConvexOverlapArea(a, b), 0.5, 1e-12);
  const std::vector<Eigen::Vector2d> far = {{5, 5}, {6, 5}, {6, 6}};
  EXPECT_EQ(ConvexOverlapArea(a, far), 0.0);
}

TEST(BodyClearance, ASubsetOfObstaclesByIndexIsJudgedAsThatSubset) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  TerrainBox under;  // the body's centre, in its band
  under.center_world_m = {0.0, 0.0, 0.1};
  under.size_m = {0.1, 0.1, 0.2};
  TerrainBox beside = under;  // half the body's footprint
  beside.center_world_m.x() = robot.body.max_m.x();
  beside.size_m = {robot.body.length_m(), 1.0, 0.2};
  TerrainBox far = under;
  far.center_world_m.x() = 5.0;
  const std::vector<BodyObstacle> obstacles = BoxBodyObstacles({under, beside, far});
  const double all = BodyOverlapShare(robot.body, obstacles, 0.0, 0.0, 0.0, 0.0);
  EXPECT_GT(all, 0.0);
  EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, {0, 1, 2}, 0.0, 0.0, 0.0, 0.0), all);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, {k}, 0.0, 0.0, 0.0, 0.0),
              BodyOverlapShare(robot.body, {obstacles[static_cast<size_t>(k)]}, 0.0, 0.0, 0.0, 0.0))
        << "obstacle " << k;
  }
  EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, {2}, 0.0, 0.0, 0.0, 0.0), 0.0);
  EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, std::vector<int>{}, 0.0, 0.0, 0.0, 0.0), 0.0);
  EXPECT_LT(BodyOverlapShare(robot.body, obstacles, {0}, 0.0, 0.0, 0.0, 0.0), all);  // the wide one decides
}

// The index's nearby obstacles judge every pose as all the obstacles do: many small
// prisms (a scan's), a few long walls over several buckets and one larger than the bucket
// limit, poses at random headings and heights.
TEST(BodyObstacleIndex, TheObstaclesNearAPoseJudgeItAsAllObstaclesDo) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> xy(-3.0, 3.0), size(0.02, 0.2), z(-0.1, 0.4), yaw(-M_PI, M_PI);
  std::vector<TerrainBox> boxes;
  for (int k = 0; k < 400; ++k) {
    TerrainBox b;
    b.center_world_m = {xy(rng), xy(rng), z(rng)};
    b.size_m = {size(rng), size(rng), 0.3};
    b.rpy_rad.z() = k % 3 == 0 ? yaw(rng) : 0.0;
    boxes.push_back(b);
  }
  TerrainBox wall;
  wall.center_world_m = {0.0, 1.0, 0.2};
  wall.size_m = {4.0, 0.05, 0.4};
  boxes.push_back(wall);
  TerrainBox huge;  // more buckets than the index lists an obstacle in
  huge.center_world_m = {0.0, 0.0, 2.0};
  huge.size_m = {500.0, 500.0, 0.1};
  boxes.push_back(huge);
  const std::vector<BodyObstacle> obstacles = BoxBodyObstacles(boxes);
  const BodyObstacleIndex index(obstacles, 0.25);
  EXPECT_EQ(index.size(), obstacles.size());
  const double radius = BodyRadius(robot.body);
  int met = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector2d c(xy(rng), xy(rng));
    const double heading = yaw(rng), ground = z(rng);
    const std::vector<int> near = index.Near(c, radius);
    EXPECT_TRUE(std::is_sorted(near.begin(), near.end()));
    const double all = BodyOverlapShare(robot.body, obstacles, c.x(), c.y(), heading, ground);
    EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, near, c.x(), c.y(), heading, ground), all) << c.transpose();
    met += all > 0.0;
    EXPECT_LT(near.size(), obstacles.size() / 4);
  }
  EXPECT_GT(met, 100);
}

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1) {
  return MakeRegionFromPolygon(id, {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, 0.0);
}

TEST(StanceRoute, KeepsTheBodyClearOfAWallOverFloor) {
  // Floor everywhere; a tall wall across the straight line that the feet could step past
  // (the floor's regions run under it): only the body check sees it.
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const std::vector<ConvexRegion> regions = {Rect(0, -0.5, -1.0, 1.5, 1.0)};
  TerrainBox wall;
  wall.center_world_m = {0.5, -0.2, 0.25};
  wall.size_m = {0.05, 1.0, 0.5};
  const std::vector<BodyObstacle> obstacles = BoxBodyObstacles({wall});
  const StanceRoute blind = PlanStanceRoute(robot, regions, {0, 0}, 0.0, {1, 0}, 0.0);
  ASSERT_TRUE(blind.found);
  const StanceRoute s = PlanStanceRoute(robot, regions, obstacles, 0.0, {0, 0}, 0.0, {1, 0}, 0.0);
  ASSERT_TRUE(s.found);
  EXPECT_GT(s.body_blocked_poses, 0);
  ASSERT_EQ(s.yaws_rad.size(), s.route.size());
  for (size_t k = 0; k < s.route.size(); ++k) {
    EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, s.route[k].x(), s.route[k].y(), s.yaws_rad[k], 0.0), 0.0)
        << s.route[k].transpose();
  }
  EXPECT_GT(s.length_m, blind.length_m + 0.1);
}

// A wall across the floor with an opening wider than the body by twice the route's body
// margin and a little: the route keeps the margin through it rather than hugging the
// opening's edge on the shortest line.
TEST(StanceRoute, KeepsTheBodyMarginThroughAnOpeningWhereThereIsRoom) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const std::vector<ConvexRegion> regions = {Rect(0, -0.5, -1.5, 1.5, 1.5)};
  const StanceRouteOptions options;
  const double opening = robot.body.width_m() + 2 * options.body_margin_m + 0.06;
  TerrainBox below, above;  // the wall's two parts, the opening y in [0.3, 0.3 + opening]
  below.center_world_m = {0.5, 0.3 - 0.75, 0.25};
  below.size_m = {0.05, 1.5, 0.5};
  above = below;
  above.center_world_m.y() = 0.3 + opening + 0.75;
  const std::vector<BodyObstacle> obstacles = BoxBodyObstacles({below, above});
  const StanceRoute s = PlanStanceRoute(robot, regions, obstacles, 0.0, {0, 0}, 0.0, {1, 0}, 0.0, options);
  ASSERT_TRUE(s.found);
  ASSERT_EQ(s.yaws_rad.size(), s.route.size());
  BodyExtent grown = robot.body;
  grown.min_m -= Eigen::Vector2d::Constant(options.body_margin_m);
  grown.max_m += Eigen::Vector2d::Constant(options.body_margin_m);
  bool passed = false;
  for (size_t k = 1; k + 1 < s.route.size(); ++k) {  // start and goal are given, not chosen
    EXPECT_EQ(BodyOverlapShare(grown, obstacles, s.route[k].x(), s.route[k].y(), s.yaws_rad[k], 0.0), 0.0)
        << s.route[k].transpose() << " yaw " << s.yaws_rad[k];
    passed = passed || std::abs(s.route[k].x() - 0.5) < 0.03;
  }
  EXPECT_TRUE(passed);
}

// Random walls over a floor: wherever the route is found, each of its chosen poses (all
// but the given start and goal) is clear by the exact overlap test at the route's yaw, and
// where it is not found, the same search without the walls finds one (the walls block).
TEST(StanceRoute, EveryRoutePoseIsClearByTheExactTestAmongRandomWalls) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const std::vector<ConvexRegion> regions = {Rect(0, -0.6, -1.2, 2.6, 1.2)};
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> x(0.3, 1.7), y(-1.0, 1.0), len(0.1, 0.8), yaw(0.0, M_PI);
  int found = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<TerrainBox> walls(4);
    for (TerrainBox& w : walls) {
      w.center_world_m = {x(rng), y(rng), 0.25};
      w.size_m = {len(rng), 0.05, 0.5};
      w.rpy_rad = {0.0, 0.0, yaw(rng)};
    }
    const std::vector<BodyObstacle> obstacles = BoxBodyObstacles(walls);
    const StanceRoute s = PlanStanceRoute(robot, regions, obstacles, 0.0, {-0.2, 0}, 0.0, {2.2, 0}, 0.0);
    if (!s.found) {
      EXPECT_TRUE(PlanStanceRoute(robot, regions, {-0.2, 0}, 0.0, {2.2, 0}, 0.0).found) << "trial " << trial;
      continue;
    }
    ++found;
    ASSERT_EQ(s.yaws_rad.size(), s.route.size());
    for (size_t k = 1; k + 1 < s.route.size(); ++k) {
      EXPECT_EQ(BodyOverlapShare(robot.body, obstacles, s.route[k].x(), s.route[k].y(), s.yaws_rad[k], 0.0), 0.0)
          << "trial " << trial << " pose " << s.route[k].transpose() << " yaw " << s.yaws_rad[k];
    }
  }
  EXPECT_GT(found, 6);
}

// The hexapod's baffle slalom (seed 2): before each pose was expanded once, a distance
// rounded up to float passed the double `<` again and again, and the search re-expanded
// poses until its deadline (millions of queue entries for 156,000 poses).
TEST(StanceRoute, ExpandsEachPoseAtMostOnceThroughABaffleSlalom) {
  const RobotModel robot = LoadRobot(RobotPath("hexapod"));
  const Course course = GenerateCourse(robot, RobotPath("hexapod"), CourseKind::kBaffles, 2);
  const std::vector<ConvexRegion> regions = TopFaceRegions(course.terrain, course.edge_margin_m, robot.max_slope_rad);
  const std::vector<BodyObstacle> obstacles = BoxBodyObstacles(course.terrain.boxes);
  const Eigen::Vector2d start(course.start.x_m, course.start.y_m), goal(course.goal.x_m, course.goal.y_m);
  const StanceRoute s =
      PlanStanceRoute(robot, regions, obstacles, 0.0, start, course.start.yaw_rad, goal, course.goal.yaw_rad);
  ASSERT_TRUE(s.found);
  EXPECT_GT(s.body_blocked_poses, 0);
  // Start and goal are not classified; every other expanded pose was, once.
  EXPECT_LE(s.expanded_poses, s.classified_poses + 2);
  EXPECT_GT(s.expanded_poses, 100);
}

constexpr double kCourseTimeLimit_s = 30.0;

TEST(BodyCourses, ARobotThatMustTurnToPassADoorTurns) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const Course course = GenerateCourse(robot, RobotPath("littledog"), CourseKind::kDoorway, 3);
  // Facing the start's way, the body does not fit through the door.
  const std::vector<BodyObstacle> boxes = BoxBodyObstacles(course.terrain.boxes);
  double door_x = 0.0;
  for (const TerrainBox& b : course.terrain.boxes) {
    if (b.size_m.z() > 0.3) door_x = b.center_world_m.x();
  }
  EXPECT_GT(BodyOverlapShare(robot.body, boxes, door_x, 0.0, course.start.yaw_rad, 0.0), 0.0);
  const CourseOutcome out = PlanCourse(course, robot, kCourseTimeLimit_s);
  EXPECT_TRUE(out.verdict.valid) << out.verdict.cause << " " << out.plan.message;
  EXPECT_TRUE(out.verdict.body_clear) << out.verdict.body_overlap_share;
  EXPECT_TRUE(out.verdict.reaches_goal) << ToString(out.plan.status);
  double largest_turn = 0.0;
  for (const Footstep& f : out.plan.footsteps) {
    largest_turn = std::max(largest_turn, std::abs(std::remainder(f.yaw_rad - course.start.yaw_rad, 2 * M_PI)));
  }
  EXPECT_GT(largest_turn, 0.5);
}

// The same door narrowed below the body's width and length: the feet's region graph still
// connects (the floor runs under the wall's ends), but no heading fits the body through,
// so the plan answers 'no route' naming the body rather than walking through the wall.
TEST(BodyCourses, ADoorNarrowerThanTheBodyAtEveryHeadingIsNoRouteForTheBody) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  Course course = GenerateCourse(robot, RobotPath("littledog"), CourseKind::kDoorway, 3);
  const double narrow = 0.5 * std::min(robot.body.width_m(), robot.body.length_m());
  for (TerrainBox& b : course.terrain.boxes) {
    if (b.size_m.z() < 0.3) continue;  // the floor
    const double inner = std::abs(b.center_world_m.y()) - 0.5 * b.size_m.x();  // the door's half-width
    b.center_world_m.y() -= std::copysign(inner - 0.5 * narrow, b.center_world_m.y());
  }
  const CourseOutcome out = PlanCourse(course, robot, kCourseTimeLimit_s);
  EXPECT_EQ(out.plan.status, SolveStatus::kNoRoute) << out.plan.message;
  EXPECT_NE(out.plan.message.find("no route for the body"), std::string::npos) << out.plan.message;
  EXPECT_TRUE(out.plan.footsteps.empty());
  // The message names where: a refused pose at the door, within a body's length of its wall.
  double door_x = 0.0;
  for (const TerrainBox& b : course.terrain.boxes) {
    if (b.size_m.z() > 0.3) door_x = b.center_world_m.x();
  }
  const size_t at = out.plan.message.find("nearest the goal at (");
  ASSERT_NE(at, std::string::npos) << out.plan.message;
  double x = 0.0, y = 0.0;
  ASSERT_EQ(std::sscanf(out.plan.message.c_str() + at, "nearest the goal at (%lf, %lf)", &x, &y), 2) << out.plan.message;
  EXPECT_LT(std::abs(x - door_x), std::max(robot.body.length_m(), robot.body.width_m())) << out.plan.message;
}

TEST(BodyCourses, AUShapedPocketIsWalkedAroundNotThrough) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const Course course = GenerateCourse(robot, RobotPath("littledog"), CourseKind::kPocket, 5);
  const CourseOutcome out = PlanCourse(course, robot, kCourseTimeLimit_s);
  EXPECT_TRUE(out.verdict.body_clear) << out.verdict.body_overlap_share;
  EXPECT_TRUE(out.verdict.valid) << out.verdict.cause;
  EXPECT_TRUE(out.verdict.reaches_goal) << ToString(out.plan.status);
  // Without the body obstacles the checker sees the body go through the pocket's back wall
  // or plans the same clear way; with them, never through.
  double widest = 0.0;
  for (const Footstep& f : out.plan.footsteps) widest = std::max(widest, std::abs(f.position_world_m.y()));
  EXPECT_GT(widest, 0.2);
}

// On the course's voxel map the planner knows only the map's obstacles (occupied voxels
// above the floor, merged into prisms), never the true boxes; the checker judges the body
// against the true boxes. The baffles' openings are a few per cent of the floor, kept by
// the region cover's necks.
TEST(BodyCourses, AVoxelMapPlanThroughABaffleSlalomKeepsTheBodyClearOfTheTrueBoxes) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const Course course = GenerateCourse(robot, RobotPath("littledog"), CourseKind::kBaffles, 37);
  const CourseOutcome out = PlanCourse(course, robot, kCourseTimeLimit_s, /*from_map=*/true);
  ASSERT_FALSE(out.body_obstacles.empty());
  for (const BodyObstacle& o : out.body_obstacles) {
    // The map's prisms stand above the floor (top at z = 0): walls only.
    EXPECT_GT(o.top_z_m, robot.body.bottom_m);
  }
  EXPECT_TRUE(out.verdict.valid) << out.verdict.cause << " " << out.plan.message;
  EXPECT_TRUE(out.verdict.body_clear) << out.verdict.body_overlap_share;
  EXPECT_TRUE(out.verdict.reaches_goal) << ToString(out.plan.status) << " " << out.plan.message;
}

TEST(WindowBodyCheck, NamesTheFirstConfigurationWhoseBodyMeetsAnObstacle) {
  const RobotModel robot = LoadRobot(RobotPath("littledog"));
  const std::vector<ConvexRegion> regions = {Rect(0, -0.5, -1.0, 1.5, 1.0)};
  TerrainBox wall;  // along x, its near face at y = 0.175
  wall.center_world_m = {0.0, 0.2, 0.25};
  wall.size_m = {1.0, 0.05, 0.5};
  PlanRequest request;
  request.start_feet_world_m = NominalStance(robot, regions, 0.0, 0.0, 0.0);
  request.goal_x_m = 1.0;
  request.body_obstacles = BoxBodyObstacles({wall});
  const PlannerOptions options;
  const std::vector<RelaxationSolver*> none;
  const PlanContext context(robot, regions, request, options, none);
  // The start stance, then the same feet under a body turned by a quarter, then by none.
  std::vector<Footstep> steps;
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    Footstep f;
    f.leg = leg;
    f.position_world_m = request.start_feet_world_m[leg];
    steps.push_back(f);
  }
  for (int leg = 0; leg < robot.num_legs(); ++leg) steps.push_back(steps[leg]);
  EXPECT_FALSE(WindowBodyClash(context, steps, 4).has_value());
  // Moved 0.1 m toward the wall, the body's half-width (0.06 m) stays clear of it; its
  // half-length (0.1 m), turned across, does not.
  for (size_t k = 4; k < 8; ++k) steps[k].position_world_m.y() += 0.1;
  EXPECT_FALSE(WindowBodyClash(context, steps, 4).has_value());
  steps[6].yaw_rad = M_PI / 2;
  const std::optional<std::string> clash = WindowBodyClash(context, steps, 4);
  ASSERT_TRUE(clash.has_value());
  EXPECT_NE(clash->find("step 3 of the window"), std::string::npos) << *clash;
  EXPECT_FALSE(WindowBodyClash(context, steps, 2).has_value());  // trimmed steps are never walked
  // No obstacles, no check.
  PlanRequest open = request;
  open.body_obstacles.clear();
  const PlanContext open_context(robot, regions, open, options, none);
  EXPECT_FALSE(WindowBodyClash(open_context, steps, 4).has_value());
}

}  // namespace
}  // namespace mfp
