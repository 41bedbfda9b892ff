#pragma once
// SVG drawing of a plan: regions and footsteps from above (one colour per leg, steps
// numbered, start and goal marked) and a side profile of heights below it.
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "planner/formulation/plan.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct SvgGoal {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
};

std::string PlanToSvg(const Plan& plan, const RobotModel& robot,
                      const std::vector<ConvexRegion>& regions, const SvgGoal& goal,
                      const std::string& title);

}  // namespace mfp
