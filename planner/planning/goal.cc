#include "planner/planning/internal/goal.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {
namespace {


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
  for (const ConvexRegion& r : regions) best = std::min(best, PlanDistanceToRegion(r, xy));
  return best;
}

}  // namespace mfp
