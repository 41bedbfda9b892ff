#pragma once
// The plan JSON of DESIGN.md (mfp-plan --json). Extensions beyond the contract are
// documented in the README: "message", "relaxations", "windows", "steps".
#include <nlohmann/json.hpp>
#include <vector>

#include "planner/formulation/plan.h"
#include "planner/robot/robot_model.h"
#include "terrain/convex_region.h"

namespace mfp {

nlohmann::json PlanToJson(const Plan& plan, const RobotModel& robot,
                          const std::vector<ConvexRegion>& regions);

}  // namespace mfp
