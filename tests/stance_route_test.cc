// The route over stance poses (planner/planning/internal/stance_route.h), on layouts built by hand.
#include <gtest/gtest.h>

#include <atomic>

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
