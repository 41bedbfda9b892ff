#include "planner/planning/internal/goal.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "base/check.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {
namespace {

struct Candidate {
  double cost = 0.0;  // largest foot move the pose asks for [m]
  GoalPose pose;
};

// The regions a foot spot of a pose within max_shift_m of the goal can lie on.
std::vector<ConvexRegion> RegionsNear(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                      const GoalPose& goal, double max_shift_m, double tolerance_m) {
  const double radius = max_shift_m + LegReach(robot) + tolerance_m;
  std::vector<ConvexRegion> near;
  for (const ConvexRegion& r : regions) {
    if (PlanDistanceToRegion(r, Eigen::Vector2d(goal.x_m, goal.y_m)) <= radius) near.push_back(r);
  }
  return near;
}

std::vector<Candidate> CandidatePoses(const RobotModel& robot, const GoalPose& goal, double max_shift_m,
                                      double max_turn_rad, double step_m, double yaw_step_rad) {
  const int cells = static_cast<int>(std::floor(max_shift_m / step_m + 1e-9));
  const int turns = max_turn_rad > 0.0 ? static_cast<int>(std::ceil(max_turn_rad / yaw_step_rad - 1e-9)) : 0;
  const double reach = LegReach(robot);
  std::vector<Candidate> out;
  for (int t = -turns; t <= turns; ++t) {
    const double turn = turns == 0 ? 0.0 : max_turn_rad * t / turns;
    for (int i = -cells; i <= cells; ++i) {
      for (int j = -cells; j <= cells; ++j) {
        const double shift = step_m * std::hypot(i, j);
        if (shift > max_shift_m + 1e-9) continue;
        out.push_back({shift + reach * std::abs(turn), {goal.x_m + step_m * i, goal.y_m + step_m * j, goal.yaw_rad + turn}});
      }
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  return out;
}

// The first candidate pose, nearest first (CandidatePoses), that `holds`; nullopt when none
// does or the deadline expires (checked every 64 candidates).
std::optional<GoalPose> FirstCandidateWhere(const RobotModel& robot, const GoalPose& goal, double max_shift_m,
                                            double max_turn_rad, double step_m, double yaw_step_rad,
                                            const Deadline& deadline,
                                            const std::function<bool(const GoalPose&)>& holds) {
  const std::vector<Candidate> candidates = CandidatePoses(robot, goal, max_shift_m, max_turn_rad, step_m, yaw_step_rad);
  for (size_t k = 0; k < candidates.size(); ++k) {
    if (k % 64 == 0 && deadline.Expired()) return std::nullopt;
    if (holds(candidates[k].pose)) return candidates[k].pose;
  }
  return std::nullopt;
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
  for (const ConvexRegion& r : regions) best = std::min(best, PlanDistanceToRegion(r, xy));
  return best;
}

int LegOffRegions(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const GoalPose& pose,
                  double tolerance_m) {
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d spot = NominalFootXY(robot, leg, pose.x_m, pose.y_m, pose.yaw_rad);
    bool on = false;
    for (const ConvexRegion& r : regions) on = on || PlanDistanceToRegion(r, spot) <= tolerance_m;
    if (!on) return leg;
  }
  return -1;
}

std::optional<GoalPose> NearestCertifiedGoal(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                             const GoalPose& goal, double max_shift_m, double max_turn_rad,
                                             double step_m, double yaw_step_rad, double tolerance_m,
                                             const Deadline& deadline) {
  MFP_CHECK(step_m > 0.0 && yaw_step_rad > 0.0 && max_shift_m >= 0.0 && max_turn_rad >= 0.0);
  const std::vector<ConvexRegion> near = RegionsNear(robot, regions, goal, max_shift_m, tolerance_m);
  if (near.empty()) return std::nullopt;
  return FirstCandidateWhere(robot, goal, max_shift_m, max_turn_rad, step_m, yaw_step_rad, deadline,
                             [&](const GoalPose& pose) { return LegOffRegions(robot, near, pose, tolerance_m) < 0; });
}

std::optional<GoalPose> NearestGoalWith(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                        const GoalPose& goal, double max_shift_m, double max_turn_rad, double step_m,
                                        double yaw_step_rad, const std::function<bool(const Eigen::Vector2d&)>& off_regions,
                                        const Deadline& deadline) {
  MFP_CHECK(step_m > 0.0 && yaw_step_rad > 0.0 && max_shift_m >= 0.0 && max_turn_rad >= 0.0);
  const std::vector<ConvexRegion> near = RegionsNear(robot, regions, goal, max_shift_m, 0.0);
  return FirstCandidateWhere(robot, goal, max_shift_m, max_turn_rad, step_m, yaw_step_rad, deadline,
                             [&](const GoalPose& pose) {
                               for (int leg = 0; leg < robot.num_legs(); ++leg) {
                                 const Eigen::Vector2d spot = NominalFootXY(robot, leg, pose.x_m, pose.y_m, pose.yaw_rad);
                                 if (!(DistanceToNearestRegion(near, spot) <= 0.0 || off_regions(spot))) return false;
                               }
                               return true;
                             });
}

}  // namespace mfp
