#include "planner/planning/goal.h"

#include <algorithm>
#include <cmath>

#include "planner/base/check.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {
namespace {

// Distance in plan view from q to a region's polygon (0 inside).
double PlanarDistance(const ConvexRegion& region, const Eigen::Vector2d& q) {
  const auto& v = region.vertices_world_m;
  bool inside = true;
  double best = kInfinity;
  for (size_t k = 0; k < v.size(); ++k) {
    const Eigen::Vector2d a = v[k].head<2>(), b = v[(k + 1) % v.size()].head<2>();
    const Eigen::Vector2d e = b - a;
    if (e.x() * (q - a).y() - e.y() * (q - a).x() < 0) inside = false;
    const double t = std::clamp((q - a).dot(e) / std::max(e.squaredNorm(), 1e-18), 0.0, 1.0);
    best = std::min(best, (a + t * e - q).norm());
  }
  return inside ? 0.0 : best;
}

}  // namespace

GoalDistances DistancesToGoal(const RobotModel& robot, const std::vector<Footstep>& footsteps, const GoalSpec& goal) {
  const int n = robot.num_legs();
  const int size = static_cast<int>(footsteps.size());
  MFP_CHECK(size >= n);
  GoalDistances d;
  for (int i = size - n; i < size; ++i) {
    const Eigen::Vector2d g = NominalFootXY(robot, footsteps[i].leg, goal.x_m, goal.y_m, goal.yaw_rad);
    d.foot_m.push_back((footsteps[i].position_world_m.head<2>() - g).norm());
  }
  d.yaw_rad = std::abs(std::remainder(FinalStanceYaw(robot, footsteps) - goal.yaw_rad, 2 * M_PI));
  return d;
}

bool WithinGoal(const GoalDistances& d, const GoalSpec& goal, double slack_m, double slack_rad) {
  for (double foot : d.foot_m) {
    if (foot > goal.tolerance_m + slack_m) return false;
  }
  return d.yaw_rad <= goal.yaw_tolerance_rad + slack_rad;
}

double DistanceToNearestRegion(const std::vector<ConvexRegion>& regions, const Eigen::Vector2d& xy) {
  double best = kInfinity;
  for (const ConvexRegion& r : regions) best = std::min(best, PlanarDistance(r, xy));
  return best;
}

}  // namespace mfp
