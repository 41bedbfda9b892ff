// A start stance on a floor of tiles beside a rotated landing (issue 29): feet 10 cm
// inside the real surface, one of them on the tiles' seam, are on the top-face regions
// (the faces of one height are inset as one surface), so the request is accepted without
// a seen surface to fall back on.
#include <gtest/gtest.h>

#include <cmath>

#include "planner/planning/request_check.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

TerrainBox Box(const Eigen::Vector3d& top_centre, const Eigen::Vector3d& size, double yaw_rad = 0.0) {
  TerrainBox b;
  b.size_m = size;
  b.rpy_rad = {0, 0, yaw_rad};
  b.center_world_m = top_centre - Eigen::Vector3d(0, 0, size.z() / 2);
  return b;
}

// Distance-like clearance of (x, y) from a box's footprint in its own frame: positive
// outside, at least the true distance's lower bound along either box axis [m].
double OutsideFootprintBy(const TerrainBox& box, const Eigen::Vector3d& p) {
  const Eigen::Vector3d local = BoxRotation(box).transpose() * (p - box.center_world_m);
  return std::max(std::abs(local.x()) - box.size_m.x() / 2, std::abs(local.y()) - box.size_m.y() / 2);
}

TEST(SeamStartTest, AStanceOnTheSeamsOfATiledFloorBesideARotatedLandingIsAccepted) {
  Course course = LoadCourse("hexapod_flat.yaml");
  Scenario& s = course.scenario;
  s.terrain.boxes.clear();
  for (double x : {-1.0, 1.0}) {
    for (double y : {-1.0, 1.0}) s.terrain.boxes.push_back(Box({x, y, 0.0}, {2.0, 2.0, 0.1}));
  }
  const TerrainBox landing = Box({0.6, 0.6, 0.6}, {0.8, 0.8, 0.6}, M_PI / 6);
  s.terrain.boxes.push_back(landing);
  s.boxes_source = BoxRegionSource::kTopFaces;
  const std::vector<ConvexRegion> regions = ScenarioRegions(s, course.robot);
  // The scenario's stance moved so that its first foot stands on the seam x = 0.
  PlanRequest request = course.request;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& f : request.start_feet_world_m) centre += f / double(request.start_feet_world_m.size());
  const Eigen::Vector3d shift(-request.start_feet_world_m[0].x(), -0.55 - centre.y(), 0.0);
  for (Eigen::Vector3d& f : request.start_feet_world_m) {
    f += shift;
    f.z() = 0.0;
    // 10 cm inside the real floor: from its outer edges and from the landing standing on it.
    EXPECT_LE(std::max(std::abs(f.x()), std::abs(f.y())), 1.9) << f.transpose();
    EXPECT_GE(OutsideFootprintBy(landing, f), 0.1) << f.transpose();
  }
  EXPECT_NEAR(request.start_feet_world_m[0].x(), 0.0, 1e-12);
  request.start_yaw_rad = 0.0;
  request.goal_x_m = -1.0;
  request.goal_y_m = -1.0;
  request.seen_surface = nullptr;  // every start foot must be on a region
  const RequestCheck check = CheckPlanRequest(course.robot, regions, request, s.options);
  EXPECT_TRUE(check.ok()) << check.message;
  for (const Eigen::Vector3d& f : request.start_feet_world_m) {
    EXPECT_GE(FindRegionBelow(regions, f.x(), f.y(), 0.0), 0) << f.transpose();
  }
}

}  // namespace
}  // namespace mfp
