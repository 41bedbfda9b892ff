#include "daemon/internal/request_validation.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "base/format.h"
#include "planner/planning/request_check.h"

namespace mfp {
namespace {

ValidatedRequest Reject(SolveStatus status, const std::string& message,
                        const std::string& robot_name = "") {
  ValidatedRequest result;
  result.ok = false;
  result.status = status;
  result.message = message;
  result.robot_name = robot_name;
  return result;
}

// First non-finite number of the request, named ("start_feet[2][1] = nan"), or "".
std::string FirstNonFinite(const plan_request_t& m) {
  for (size_t i = 0; i < m.start_feet.size(); ++i) {
    for (size_t j = 0; j < m.start_feet[i].size(); ++j) {
      if (!std::isfinite(m.start_feet[i][j]))
        return "start_feet[" + std::to_string(i) + "][" + std::to_string(j) + "] = " +
               Number(m.start_feet[i][j]);
    }
  }
  const std::pair<const char*, double> scalars[] = {{"goal_x", m.goal_x},
                                                    {"goal_y", m.goal_y},
                                                    {"goal_yaw", m.goal_yaw},
                                                    {"time_limit_s", m.time_limit_s}};
  for (const auto& [name, value] : scalars) {
    if (!std::isfinite(value)) return std::string(name) + " = " + Number(value);
  }
  return "";
}

}  // namespace

ValidatedRequest ValidateRequest(const plan_request_t& m,
                                 const std::map<std::string, RobotModel>& robots,
                                 const std::string& default_robot,
                                 const std::vector<ConvexRegion>* regions,
                                 std::shared_ptr<const SeenSurface> seen_surface,
                                 const DaemonLimits& limits, const PlannerOptions& options) {
  if (const std::string bad = FirstNonFinite(m); !bad.empty())
    return Reject(SolveStatus::kInvalidRequest, "not a finite number: " + bad);

  const std::string name = m.robot.empty() ? default_robot : m.robot;
  const auto found = robots.find(name);
  if (found == robots.end()) {
    std::string known;
    for (const auto& entry : robots) known += (known.empty() ? "" : ", ") + entry.first;
    return Reject(SolveStatus::kInvalidRequest,
                  "robot: unknown robot '" + name + "' (known: " + known + ")");
  }
  const RobotModel& robot = found->second;
  if (m.num_legs != robot.num_legs())
    return Reject(SolveStatus::kInvalidRequest,
                  "num_legs = " + std::to_string(m.num_legs) + " but robot '" + name + "' has " +
                      std::to_string(robot.num_legs()) + " legs",
                  name);
  if (m.max_steps < 0 || m.max_steps > limits.max_steps)
    return Reject(SolveStatus::kInvalidRequest,
                  "max_steps = " + std::to_string(m.max_steps) + " is outside [0, " +
                      std::to_string(limits.max_steps) + "] (0 = default)",
                  name);
  if (m.time_limit_s < 0 || m.time_limit_s > limits.max_time_limit_s)
    return Reject(SolveStatus::kInvalidRequest,
                  "time_limit_s = " + Number(m.time_limit_s) + " is outside [0, " +
                      Number(limits.max_time_limit_s) + "] s (0 = default)",
                  name);
  if (regions == nullptr)
    return Reject(SolveStatus::kNoMap, "no terrain map received yet on MFP_TERRAIN_MAP or MFP_HEIGHT_MAP", name);
  if (regions->empty())
    return Reject(SolveStatus::kNoMap, "the current terrain map has no safe regions", name);

  // The start feet are checked once, by the planner's CheckPlanRequest below.
  PlanRequest request;
  for (int leg = 0; leg < m.num_legs; ++leg) {
    const auto& f = m.start_feet[static_cast<size_t>(leg)];
    request.start_feet_world_m.emplace_back(f[0], f[1], f[2]);
  }

  request.start_yaw_rad = EstimateStanceYaw(robot, request.start_feet_world_m);
  request.goal_x_m = m.goal_x;
  request.goal_y_m = m.goal_y;
  request.goal_yaw_rad = m.goal_yaw;
  request.max_steps = m.max_steps > 0 ? m.max_steps : limits.default_max_steps;
  request.time_limit_s = m.time_limit_s > 0 ? m.time_limit_s : limits.default_time_limit_s;
  request.seen_surface = std::move(seen_surface);

  // The planner's own checks (ranges, start feet on regions or the seen surface, the goal
  // within reach). A goal beyond reach of every region is left to the planning thread:
  // the planner answers it invalid_goal naming the nearest stance on regions, a search of
  // up to goal_search.report_radius that runs there under the request's deadline, not on
  // the intake thread.
  if (const RequestCheck check = CheckPlanRequest(robot, *regions, request, options);
      !check.ok() && check.status != SolveStatus::kInvalidGoal)
    return Reject(check.status, check.message, name);

  ValidatedRequest result;
  result.ok = true;
  result.status = SolveStatus::kOptimal;
  result.robot_name = name;
  result.request = std::move(request);
  return result;
}

}  // namespace mfp
