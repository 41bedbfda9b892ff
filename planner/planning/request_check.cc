#include "planner/planning/request_check.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "geometry/seen_surface.h"
#include "planner/planning/internal/goal.h"

namespace mfp {
namespace {

RequestCheck Rejection(SolveStatus status, const std::string& message) { return RequestCheck{status, message}; }

int ChooseValue(int requested, int fallback) { return requested > 0 ? requested : fallback; }

// "" or why the yaws are refused: a heading beyond one turn either way is a mistake (a
// goal yaw of 1e16 rad would have the planner turn on the spot until its steps ran out).
std::string YawProblem(const PlanRequest& request) {
  const std::pair<const char*, double> yaws[] = {{"start yaw", request.start_yaw_rad},
                                                 {"goal yaw", request.goal_yaw_rad}};
  for (const auto& [name, yaw] : yaws) {
    if (std::abs(yaw) > kMaxRequestYawRad) {
      std::ostringstream msg;
      msg << name << " = " << yaw << " rad is outside [-2 pi, 2 pi] (one turn either way); give the "
          << "heading in radians";
      return msg.str();
    }
  }
  return "";
}

// "" or why the start stance is degenerate: every foot within kMinStanceSpreadM of one
// point is no stance a robot can stand in (and gives the planner no heading).
std::string StanceProblem(const std::vector<Eigen::Vector3d>& feet) {
  if (feet.size() < 2) return "";
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& f : feet) centre += f / static_cast<double>(feet.size());
  double spread = 0.0;
  for (const Eigen::Vector3d& f : feet) spread = std::max(spread, (f - centre).norm());
  if (spread >= kMinStanceSpreadM) return "";
  std::ostringstream msg;
  msg << "start_feet: all " << feet.size() << " start feet are within " << spread
      << " m of one point (" << centre.x() << ", " << centre.y() << ", " << centre.z()
      << "): not a stance; give each foot's own position";
  return msg.str();
}

// Plan-view radius searched for the seen surface nearest to a start foot off it [m].
constexpr double kNearestSurfaceSearchM = 2.0;

// "" or why start foot k cannot be stood on: on a region (within the start tolerance) it
// can; with a seen surface, anywhere on that surface too (the robot stands there, the
// regions only leave it out); else the message names the foot and the nearest surface.
std::string StartFootProblem(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                             const PlanRequest& request, const PlannerOptions& options, int k) {
  const Eigen::Vector3d& f = request.start_feet_world_m[k];
  const double tol = options.start_tolerance_m;
  for (const ConvexRegion& r : regions) {
    if (RegionContains(r, f, tol)) return "";
  }
  static const SeenSurface kNone;
  const SeenSurface& seen = request.seen_surface != nullptr ? *request.seen_surface : kNone;
  if (!seen.empty() && OnSeenSurface(seen, f, tol)) return "";
  std::ostringstream msg;
  msg << "start foot of leg " << k << " ('" << robot.legs[k].name << "') at (" << f.x() << ", " << f.y() << ", "
      << f.z() << ") m is not on any region";
  if (seen.empty()) {
    msg << " (tolerance " << tol << " m)";
    return msg.str();
  }
  msg << " nor on the surface the map saw from above (tolerance " << tol << " m)";
  const NearestSurfacePoint near = NearestSeenSurface(seen, f, kNearestSurfaceSearchM);
  if (near.found) {
    msg << "; the nearest seen surface is at (" << near.point_world_m.x() << ", " << near.point_world_m.y() << ", "
        << near.point_world_m.z() << ") m, " << near.distance_m << " m away";
  } else {
    msg << "; no seen surface within " << kNearestSurfaceSearchM << " m in plan view";
  }
  return msg.str();
}

}  // namespace

int MaxSteps(const RobotModel& robot, const PlanRequest& request, const PlannerOptions& options) {
  return ChooseValue(request.max_steps, ChooseValue(options.default_max_steps, 12 * robot.num_legs()));
}

int WindowSteps(const RobotModel& robot, const PlanRequest& request, const PlannerOptions& options) {
  return ChooseValue(request.window_steps, ChooseValue(options.default_window_steps, 2 * robot.num_legs()));
}

RequestCheck CheckPlanRequest(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                              const PlanRequest& request, const PlannerOptions& options) {
  const int n = robot.num_legs();
  if (regions.empty() && request.deadline.Expired()) {
    // Nothing was extracted because the time ran out (loading the robot, reading or
    // extracting the map): a time limit, not a map without surfaces.
    return Rejection(SolveStatus::kTimeLimit,
                     "time limit reached before planning: loading the robot and extracting the "
                     "terrain regions took the whole time limit; give a longer time limit");
  }
  if (regions.empty()) return Rejection(SolveStatus::kNoMap, "no terrain regions: no map yet or the map has no walkable surface");
  if (static_cast<int>(request.start_feet_world_m.size()) != n) {
    return Rejection(SolveStatus::kInvalidRequest,
                    "start stance has " + std::to_string(request.start_feet_world_m.size()) +
                        " feet; robot '" + robot.name + "' has " + std::to_string(n) + " legs");
  }
  for (int k = 0; k < n; ++k) {
    if (!request.start_feet_world_m[k].allFinite()) {
      return Rejection(SolveStatus::kInvalidRequest, "start foot of leg " + std::to_string(k) + " is not finite");
    }
  }
  if (!std::isfinite(request.start_yaw_rad) || !std::isfinite(request.goal_x_m) ||
      !std::isfinite(request.goal_y_m) || !std::isfinite(request.goal_yaw_rad) ||
      !std::isfinite(request.time_limit_s)) {
    return Rejection(SolveStatus::kInvalidRequest, "start yaw, goal pose and time limit must be finite numbers");
  }
  if (const std::string problem = YawProblem(request); !problem.empty()) {
    return Rejection(SolveStatus::kInvalidRequest, problem);
  }
  if (const std::string problem = StanceProblem(request.start_feet_world_m); !problem.empty()) {
    return Rejection(SolveStatus::kInvalidStart, problem);
  }
  const int max_steps = MaxSteps(robot, request, options);
  const int window = WindowSteps(robot, request, options);
  if (request.max_steps < 0 || max_steps > 100000 || request.window_steps < 0 || window > 1000 ||
      request.time_limit_s < 0 || request.max_windows < 0) {
    return Rejection(SolveStatus::kInvalidRequest,
                    "max_steps must be in [0, 100000], window in [0, 1000], time limit >= 0 s, max_windows >= 0");
  }
  for (int k = 0; k < n; ++k) {
    if (const std::string problem = StartFootProblem(robot, regions, request, options, k); !problem.empty()) {
      return Rejection(SolveStatus::kInvalidStart, problem);
    }
  }
  const double reach = LegReach(robot);
  const double goal_distance = DistanceToNearestRegion(regions, Eigen::Vector2d(request.goal_x_m, request.goal_y_m));
  if (goal_distance > reach + robot.l_bnd_m) {
    std::ostringstream msg;
    msg << "goal (" << request.goal_x_m << ", " << request.goal_y_m << ") m is " << goal_distance
        << " m from the nearest region; the robot's feet reach " << reach + robot.l_bnd_m << " m from its centre";
    return Rejection(SolveStatus::kInvalidGoal, msg.str());
  }
  return RequestCheck{};
}

}  // namespace mfp
