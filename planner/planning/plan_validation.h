#pragma once
// Independent check of a finished plan against the paper's constraints, recomputed from
// the footsteps alone with exact sin/cos. Used by tests, mfp-plan --validate and
// mfp-check-replies (the daemon's replies).
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "planner/formulation/plan.h"
#include "planner/planning/internal/goal.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct ValidationTolerances {
  double position_m = 1e-4;   // region faces, boxes, heights (no slack for sin/cos chords:
                              // every plan is checked with exact trigonometry)
  double yaw_rad = 1e-5;
};

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
