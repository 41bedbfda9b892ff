#pragma once
// Independent check of a finished plan against the paper's constraints, recomputed from
// the footsteps alone with exact sin/cos. Used by tests and by mfp-plan --validate.
#include <string>
#include <vector>

#include "planner/formulation/plan.h"
#include "planner/planning/goal.h"
#include "planner/robot/robot_model.h"
#include "terrain/convex_region.h"

namespace mfp {

struct ValidationTolerances {
  double position_m = 1e-4;   // region faces, boxes, heights
  // Extra slack on the reference and reachability boxes for the piecewise-linear
  // sin/cos: the chord of a yaw segment of width w is off the circle by up to ~w^2/8.
  double rotation_m = 0.0;
  double yaw_rad = 1e-5;
};

// Slack on the boxes implied by yaw segments of the given width for this robot.
double RotationTolerance(const RobotModel& robot, double yaw_segment_rad);

// Largest excess of a plan's footsteps over each limit, recomputed from the footsteps
// alone with the exact R(yaw) of each step's reported yaw and the centre of contacts of
// its n latest footsteps [m, rad]; 0 when every step is within.
struct ExactExcess {
  double region_m = 0.0;
  double reference_box_m = 0.0;     // |f_i - r_nom,i|_inf - l_bnd
  double reachability_box_m = 0.0;  // |f_i - r_nom,i-n|_inf - d_lim
  double height_m = 0.0;
  double yaw_change_rad = 0.0;
};
ExactExcess MeasureExactExcess(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const Plan& plan);

// Returns one line per violated constraint ("step 14: reachability x off by 0.012 m");
// empty when the plan satisfies every constraint. When the plan claims reaches_goal the
// final stance is checked against the goal too.
std::vector<std::string> ValidatePlan(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                      const Plan& plan, const GoalSpec& goal,
                                      const ValidationTolerances& tolerances);

}  // namespace mfp
