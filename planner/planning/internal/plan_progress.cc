#include "planner/planning/internal/plan_progress.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/check.h"
#include "planner/planning/internal/goal.h"

namespace mfp {
namespace {

// Metres of progress one radian of turn is worth: one configuration's turn (max_yaw_change)
// weighs as much as one configuration's reach (d_lim).
double MetresPerRadian(const RobotModel& robot) {
  return robot.max_yaw_change_rad > 0.0 ? robot.d_lim_m / robot.max_yaw_change_rad : 0.0;
}

}  // namespace

double RouteLeft(const RouteGuide& guide, const Eigen::Vector2d& centre, double yaw_rad, double metres_per_radian) {
  const size_t m = guide.route.size();
  if (m == 0) return 0.0;
  const bool with_yaw = guide.yaws_rad.size() == m && metres_per_radian > 0.0;
  // The route's points in (x, y, rho yaw), its yaws unwrapped along it.
  std::vector<Eigen::Vector3d> points(m);
  double unwrapped = with_yaw ? guide.yaws_rad[0] : 0.0;
  for (size_t k = 0; k < m; ++k) {
    if (with_yaw && k > 0) unwrapped += std::remainder(guide.yaws_rad[k] - guide.yaws_rad[k - 1], 2 * M_PI);
    points[k] = Eigen::Vector3d(guide.route[k].x(), guide.route[k].y(), metres_per_radian * unwrapped);
  }
  double best = std::numeric_limits<double>::infinity(), best_left = 0.0, total = 0.0;
  for (size_t k = 1; k < m; ++k) total += (points[k] - points[k - 1]).norm();
  double before = 0.0;  // arc length up to segment k's start
  for (size_t k = 1; k < m; ++k) {
    const Eigen::Vector3d a = points[k - 1], d = points[k] - points[k - 1];
    // The pose's yaw on the turn nearest the segment's start.
    const double yaw = with_yaw ? a.z() / metres_per_radian + std::remainder(yaw_rad - a.z() / metres_per_radian, 2 * M_PI)
                                : 0.0;
    const Eigen::Vector3d p(centre.x(), centre.y(), metres_per_radian * yaw);
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double e = (a + t * d - p).norm();
    if (e < best) {
      best = e;
      best_left = total - before - t * std::sqrt(len2);
    }
    before += std::sqrt(len2);
  }
  return m == 1 ? 0.0 : std::max(0.0, best_left);
}

double RemainingWay(const PlanContext& context, const std::vector<Footstep>& footsteps) {
  const RobotModel& robot = context.robot;
  const size_t n = static_cast<size_t>(robot.num_legs());
  MFP_CHECK(footsteps.size() >= n);
  std::vector<Eigen::Vector3d> stance;
  for (size_t k = footsteps.size() - n; k < footsteps.size(); ++k) stance.push_back(footsteps[k].position_world_m);
  const Eigen::Vector2d centre = StanceCentreXY(stance);
  const double rho = MetresPerRadian(robot);
  const double route_left = context.guided && context.guide.route.size() >= 2
                                ? RouteLeft(context.guide, centre, footsteps.back().yaw_rad, rho)
                                : (centre - context.GoalXY()).norm();
  const GoalDistances goal = DistancesToGoal(robot, footsteps, context.goal);
  double off_goal = rho * goal.yaw_rad;
  for (double d : goal.foot_m) off_goal = std::max(off_goal, d);
  return std::max(route_left, off_goal);
}

double MinProgressGain(const PlanContext& context) {
  return std::min(0.1 * context.robot.d_lim_m, 0.5 * context.options.goal_tolerance_m);
}

}  // namespace mfp
