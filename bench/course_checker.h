#pragma once
// An independent judge of a plan on a generated course: it looks at the true boxes the
// course was built from, never at the regions mfp extracted, and at the robot model's
// reach limits, never at the planner's formulation.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/terrain_description.h"
#include "io/scenario_yaml.h"
#include "planner/formulation/plan.h"
#include "planner/robot/robot_model.h"
#include "terrain/quality/terrain_quality.h"  // FootOnTrueSurface: the foot test against the boxes

namespace mfp {

struct CourseCheckTolerances {
  double height_m = 0.025;   // foot height against the true top face (a voxel and a bit)
  double reach_m = 0.02;     // beyond d_lim (yaw segments, rounding)
  double goal_m = 0.07;      // final feet from their goal spots (planner's 0.05 + slack)
  double goal_yaw_rad = 0.2; // final body yaw (planner's 0.15 + slack)
  double numeric_m = 1e-3;   // the solver's feasibility tolerance on region edges
  double body_share = 0.01;  // share of the body's plan box a box may cover (grid rounding)
};

struct CourseVerdict {
  bool valid = true;          // every footstep on true surface, in reach, height change in range
  bool reaches_goal = false;  // final stance at the goal
  std::string cause;          // first failure: "off_surface", "reach", "height_change", "body_collision"
  std::vector<std::string> violations;
  // The body's plan box (RobotModel::body) at every configuration (centre of contacts,
  // yaw, band above the feet's mean height) against the true boxes: the largest share of
  // it one box covers, and whether that stayed within tolerance (true when the body is unknown).
  bool body_clear = true;
  double body_overlap_share = 0.0;
};

// footsteps: the plan's list (the first n the start stance, in any leg order).
// The body judged at every configuration (after each footstep, and the start stance).
CourseVerdict CheckPlanOnCourse(const TerrainDescription& terrain, const RobotModel& robot,
                                const std::vector<Footstep>& footsteps, const Pose2D& goal,
                                double edge_margin_m, const CourseCheckTolerances& tol = {});

}  // namespace mfp
