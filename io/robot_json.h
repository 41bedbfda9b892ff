#pragma once
// The robot object of the plan JSON (DESIGN.md): name, legs [{name, nominal_offset}],
// gait, d_lim, l_bnd, dz_max, plus hips, stance height, foot radius, yaw and slope limits,
// weights and provenance. Shared by mfp-robot and the plan JSON writer.
#include <nlohmann/json.hpp>

#include "planner/robot/robot_model.h"

namespace mfp {

nlohmann::json RobotToJson(const RobotModel& robot);

}  // namespace mfp
