#pragma once
// Checks a decoded plan_request_t against the robots, the map and the daemon's limits,
// and turns it into a planner PlanRequest. Every rejection carries the status of the
// reply and a message that names the field and the allowed range.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "daemon/daemon_config.h"
#include "geometry/convex_region.h"
#include "geometry/seen_surface.h"
#include "mfp/plan_request_t.hpp"
#include "planner/planning/footstep_planner.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct ValidatedRequest {
  bool ok = false;
  SolveStatus status = SolveStatus::kInvalidRequest;  // reply status when !ok
  std::string message;                                 // names the problem when !ok
  std::string robot_name;                              // resolved ("" when unknown)
  PlanRequest request;                                 // filled when ok
};

// regions == nullptr means no map has been received yet. seen_surface (null: none) is
// the map's surface seen from above: a start foot on it is accepted where no region holds
// it, and the request carries it to the planner.
ValidatedRequest ValidateRequest(const plan_request_t& message,
                                 const std::map<std::string, RobotModel>& robots,
                                 const std::string& default_robot,
                                 const std::vector<ConvexRegion>* regions,
                                 std::shared_ptr<const SeenSurface> seen_surface,
                                 const DaemonLimits& limits, const PlannerOptions& options);

}  // namespace mfp
