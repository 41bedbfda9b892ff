#include "planner/formulation/yaw_change_limit.h"

#include "planner/formulation/internal/step_expressions.h"

namespace mfp {

void AddYawChangeLimit(StepEncoder& e, const RobotModel& robot, int cfg) {
  e.AddRow(RowKind::kYawChange, StepName("yaw_change", cfg), e.Yaw(cfg) - e.Yaw(cfg - 1), -robot.max_yaw_change_rad,
           robot.max_yaw_change_rad);
}

}  // namespace mfp
