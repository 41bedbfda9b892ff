#pragma once
// The plan JSON of DESIGN.md (mfp-plan --json). Extensions beyond the contract are
// documented in the README: "message", "relaxations", "windows", "steps".
#include <nlohmann/json.hpp>
#include <vector>

#include "geometry/convex_region.h"
#include "planner/formulation/plan.h"
#include "planner/robot/robot_model.h"

namespace mfp {

nlohmann::json PlanToJson(const Plan& plan, const RobotModel& robot,
                          const std::vector<ConvexRegion>& regions);

}  // namespace mfp
