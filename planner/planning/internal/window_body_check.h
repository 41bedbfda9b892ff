#pragma once
// The body's clearance of a window's plan: the route keeps the body clear at its poses,
// but between them a window's yaw is free, so a plan may turn the body into a wall beside
// a door. Checked at every configuration of the window's exact plan against the
// request's body obstacles (planner/robot/body_clearance.h). Private to planner/planning.
#include <optional>
#include <string>
#include <vector>

#include "planner/formulation/plan.h"
#include "planner/planning/internal/plan_context.h"

namespace mfp {

// The first configuration of `steps` (start stance first, n of them), among the first
// `kept` new steps (those the plan keeps; trimmed steps are never walked), whose body box
// overlaps a body obstacle in its band, described for the plan's message; nullopt when
// every configuration is clear, the body is unknown or there are no obstacles.
std::optional<std::string> WindowBodyClash(const PlanContext& context, const std::vector<Footstep>& steps, int kept);

}  // namespace mfp
