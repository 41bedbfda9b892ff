#pragma once
// The checks every plan request passes before planning, in one place: PlanFootsteps runs
// them, and the daemon runs them after its own checks of the message's fields.
#include <string>
#include <vector>

#include "base/solve_status.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {

// Largest |start yaw| and |goal yaw| of a request [rad]: one turn either way.
constexpr double kMaxRequestYawRad = 2.0 * 3.14159265358979323846;
// Smallest distance of the farthest start foot from the feet's centre [m]: below it the
// stance is degenerate (every foot at one point).
constexpr double kMinStanceSpreadM = 1e-3;

struct RequestCheck {
  SolveStatus status = SolveStatus::kOptimal;  // of the rejection when !ok()
  std::string message;                         // names the problem and the allowed range
  bool ok() const { return message.empty(); }
};

// Rejections: kTimeLimit (no regions and request.deadline already passed: the time ran
// out before any were extracted), kNoMap (no regions), kInvalidRequest (sizes, non-finite numbers, ranges,
// a yaw beyond kMaxRequestYawRad), kInvalidStart (every start foot within
// kMinStanceSpreadM of one point, or a start foot on no region within
// options.start_tolerance_m and, when the request carries a seen surface, not on that
// either: the message then names the nearest seen surface point),
// kInvalidGoal (the goal farther than LegReach + l_bnd from every region in plan view).
RequestCheck CheckPlanRequest(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                              const PlanRequest& request, const PlannerOptions& options);

// New footsteps of the whole plan and of one window: the request's, else the options'
// default, else 12 n and 2 n.
int MaxSteps(const RobotModel& robot, const PlanRequest& request, const PlannerOptions& options);
int WindowSteps(const RobotModel& robot, const PlanRequest& request, const PlannerOptions& options);

}  // namespace mfp
