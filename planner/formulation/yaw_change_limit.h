#pragma once
// The seed paper's limit on the body's turn between configurations:
//   yaw change      |theta_b - theta_b-1| <= max_yaw_change
// written once through a StepEncoder (the MIQP's row and the polisher's).
#include "planner/formulation/step_encoder.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// Yaw change between configurations cfg - 1 and cfg (cfg >= 1).
void AddYawChangeLimit(StepEncoder& e, const RobotModel& robot, int cfg);

}  // namespace mfp
