// The route over stance poses (planner/planning/internal/stance_route.h), on layouts built by hand.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "io/robot_loader.h"
#include "planner/planning/internal/route_guide.h"
#include "planner/planning/internal/stance_route.h"

namespace mfp {
namespace {

ConvexRegion Rect(int id, double x0, double y0, double x1, double y1, double z = 0.0) {
  return MakeRegionFromPolygon(id, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, 0.0);
}

RobotModel Littledog() { return LoadRobot(std::string(MFP_SOURCE_DIR) + "/config/robots/littledog.yaml"); }

// Every foot of the pose has a region within l_bnd of its nominal spot at some heading.
bool Supported(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const Eigen::Vector2d& p) {
  for (int h = 0; h < 8; ++h) {
    bool all = true;
    for (int leg = 0; leg < robot.num_legs() && all; ++leg) {
      const Eigen::Vector2d foot = NominalFootXY(robot, leg, p.x(), p.y(), h * M_PI / 4);
      bool near = false;
      for (const ConvexRegion& r : regions) {
        const Eigen::Vector2d lo = r.vertices_world_m[0].head<2>(), hi = r.vertices_world_m[2].head<2>();
        near = near || (foot - foot.cwiseMax(lo).cwiseMin(hi)).norm() <= robot.l_bnd_m + 0.03;
      }
      all = near;
    }
    if (all) return true;
  }
  return false;
}

TEST(StanceRoute, GoesRoundAWallWithEveryFootSupported) {
  // Start and goal pads 1 m apart with nothing between them; a corridor over the top.
  const RobotModel robot = Littledog();
  const std::vector<ConvexRegion> regions = {Rect(0, -0.2, -0.2, 0.2, 0.2), Rect(1, 0.8, -0.2, 1.2, 0.2),
                                             Rect(2, -0.2, 0.2, 1.2, 0.6)};
  const StanceRoute s = PlanStanceRoute(robot, regions, {0, 0}, 0.0, {1, 0}, 0.0);
  ASSERT_TRUE(s.found);
  double top = -1.0;
  for (const Eigen::Vector2d& p : s.route) {
    top = std::max(top, p.y());
    EXPECT_TRUE(Supported(robot, regions, p)) << p.transpose();
  }
  EXPECT_GT(top, 0.2);       // up into the corridor, not across the gap
  EXPECT_GT(s.length_m, 1.2);
}

TEST(StanceRoute, FindsNoneWhereOnlySingleFeetFit) {
  // A beam 2 cm wide: each foot could step along it, but no stance has all four on it.
  const RobotModel robot = Littledog();
  const std::vector<ConvexRegion> regions = {Rect(0, -0.2, -0.2, 0.2, 0.2), Rect(1, 0.2, -0.01, 1.0, 0.01),
                                             Rect(2, 1.0, -0.2, 1.4, 0.2)};
  EXPECT_FALSE(PlanStanceRoute(robot, regions, {0, 0}, 0.0, {1.2, 0}, 0.0).found);
}

// A field of 40 x 40 stones 0.1 m apart with the goal 4 m away: a long search.
std::vector<ConvexRegion> StoneField() {
  std::vector<ConvexRegion> regions;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) {
      const double x = 0.1 * i, y = 0.1 * j - 2.0;
      regions.push_back(Rect(static_cast<int>(regions.size()), x, y, x + 0.08, y + 0.08));
    }
  }
  return regions;
}

TEST(StanceRoute, EndsOutOfTimeWhenTheDeadlineHasPassedOrTheStopFlagIsSet) {
  const RobotModel robot = Littledog();
  const std::vector<ConvexRegion> regions = StoneField();
  const StanceRoute expired = PlanStanceRoute(robot, regions, {0.2, 0}, 0.0, {3.8, 0}, 0.0, {}, Deadline::After(0));
  EXPECT_TRUE(expired.out_of_time);
  EXPECT_FALSE(expired.found);
  std::atomic<bool> stop{true};
  const StanceRoute stopped =
      PlanStanceRoute(robot, regions, {0.2, 0}, 0.0, {3.8, 0}, 0.0, {}, Deadline().WithStop(&stop));
  EXPECT_TRUE(stopped.out_of_time);
  const StanceRoute free = PlanStanceRoute(robot, regions, {0.2, 0}, 0.0, {3.8, 0}, 0.0);
  EXPECT_FALSE(free.out_of_time);
}

// LittleDog's legs moved to a long, narrow stance (feet 0.38 m apart along the body,
// 0.08 m across, as the zoo's Go1): turned across a strip, its feet stand off it.
RobotModel LongNarrowQuadruped() {
  RobotModel robot = Littledog();
  for (LegModel& leg : robot.legs) {
    const Eigen::Vector2d o = leg.nominal_offset_body_m;
    leg.nominal_offset_body_m = Eigen::Vector2d(o.x() > 0 ? 0.19 : -0.19, o.y() > 0 ? 0.04 : -0.04);
  }
  return robot;
}

// Start pad, a strip along x of the given width, goal pad; the goal turned a quarter.
RouteGuide GuideAlongStrip(const RobotModel& robot, double strip_width_m) {
  const double w = strip_width_m / 2;
  const std::vector<ConvexRegion> regions = {Rect(0, -0.35, -0.35, 0.35, 0.35), Rect(1, 0.35, -w, 1.25, w),
                                             Rect(2, 1.25, -0.35, 1.95, 0.35)};
  std::vector<Eigen::Vector3d> feet;
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d xy = NominalFootXY(robot, leg, 0.0, 0.0, 0.0);
    feet.emplace_back(xy.x(), xy.y(), 0.0);
  }
  RouteGuide guide;
  guide.connected = true;
  guide.route = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1.6, 0)};
  FollowStanceRoute(robot, regions, {}, feet, 0.0, {1.6, 0}, M_PI / 2, StanceRouteOptions{}, &guide);
  return guide;
}

TEST(RouteGuide, CarriesTheRouteYawsWhereTheGoalsHeadingLeavesFeetOffTheRoute) {
  // Turned to the goal's heading on the 0.2 m strip, the front and hind feet stand 0.09 m
  // beyond its edges (more than l_bnd): the windows must hold the route's heading there
  // (the zoo's Go1 and ANYmal C crabbed along an uneven field's edge at the goal's yaw
  // and stalled, go1_rough_turn_29).
  const RobotModel robot = LongNarrowQuadruped();
  const RouteGuide guide = GuideAlongStrip(robot, 0.2);
  ASSERT_TRUE(guide.from_stances);
  ASSERT_EQ(guide.yaws_rad.size(), guide.route.size());
  int on_strip = 0;
  for (size_t k = 0; k < guide.route.size(); ++k) {
    if (guide.route[k].x() < 0.6 || guide.route[k].x() > 1.0) continue;
    ++on_strip;
    EXPECT_LT(std::abs(std::remainder(guide.yaws_rad[k], M_PI)), 0.1) << guide.route[k].transpose();
  }
  EXPECT_GT(on_strip, 0);
}

TEST(RouteGuide, LeavesTheYawToTheWindowsWhereTheGoalsHeadingFitsTheRoute) {
  // On a strip 0.7 m wide the goal's heading fits every route pose: no yaws (the windows
  // turn toward the goal's yaw as they walk).
  const RouteGuide guide = GuideAlongStrip(LongNarrowQuadruped(), 0.7);
  ASSERT_TRUE(guide.from_stances);
  EXPECT_TRUE(guide.yaws_rad.empty());
}

TEST(RouteGuide, TheRegionGraphEndsOutOfTimeAndSaysSoRatherThanNoRoute) {
  const RobotModel robot = Littledog();
  const std::vector<ConvexRegion> regions = StoneField();
  std::vector<Eigen::Vector3d> feet;
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d xy = NominalFootXY(robot, leg, 0.4, 0.0, 0.0);
    feet.emplace_back(xy.x(), xy.y(), 0.0);
  }
  const RouteGuide late = PlanRoute(robot, regions, feet, {3.6, 0}, 0.0, 0.1, 0.1, Deadline::After(0));
  EXPECT_TRUE(late.out_of_time);
  EXPECT_FALSE(late.connected);
  EXPECT_TRUE(late.broken.empty());
  const RouteGuide in_time = PlanRoute(robot, regions, feet, {3.6, 0}, 0.0, 0.1, 0.1);
  EXPECT_FALSE(in_time.out_of_time);
}

}  // namespace
}  // namespace mfp
