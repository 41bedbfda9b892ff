#pragma once
// The goal of a request and the one test of whether a stance reaches it: every final foot
// within a tolerance of its goal spot (its nominal foot at the goal pose) and the final
// stance's yaw, estimated from the feet, within a tolerance of the goal yaw. The planner
// stops on it; plan validation reports by it.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "base/deadline.h"
#include "geometry/convex_region.h"
#include "planner/formulation/plan.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct GoalSpec {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
  double tolerance_m = 0.05, yaw_tolerance_rad = 0.15;
};

// How far a footstep list's final stance (its last n footsteps) is from the goal.
struct GoalDistances {
  std::vector<double> foot_m;  // per final footstep, in list order: plan-view distance to its goal spot [m]
  double yaw_rad = 0.0;        // |final stance yaw - goal yaw|, wrapped to [0, pi] [rad]
};
GoalDistances DistancesToGoal(const RobotModel& robot, const std::vector<Footstep>& footsteps, const GoalSpec& goal);

// Every distance within the goal's tolerances plus the given slack.
bool WithinGoal(const GoalDistances& d, const GoalSpec& goal, double slack_m = 0.0, double slack_rad = 0.0);

// Plan-view distance from (x, y) to the nearest region's polygon (0 inside; infinity
// without regions) [m]. A goal farther than LegReach + l_bnd from every region cannot be
// stood at.
double DistanceToNearestRegion(const std::vector<ConvexRegion>& regions, const Eigen::Vector2d& xy);

struct GoalPose {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
};

// -1 when every leg's nominal foot spot at the pose lies within tolerance_m of a region's
// polygon in plan view (the route guide's test of a goal stance); else the first leg, in
// leg order, whose spot does not.
int LegOffRegions(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const GoalPose& pose,
                  double tolerance_m);

// The pose nearest to `goal` whose spots all lie on regions (LegOffRegions == -1), moved
// at most max_shift_m and turned at most max_turn_rad; positions on a grid of step_m
// about the goal, yaws in steps of at most yaw_step_rad. Nearest by the largest move of a
// foot it asks for (the shift plus LegReach times the turn). nullopt when there is none,
// or when `deadline` expires first (checked every 64 poses: a 2 m search on a large map
// tries thousands of poses against hundreds of regions; the caller tells the two apart).
std::optional<GoalPose> NearestCertifiedGoal(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                             const GoalPose& goal, double max_shift_m, double max_turn_rad,
                                             double step_m, double yaw_step_rad, double tolerance_m,
                                             const Deadline& deadline = Deadline());

// As NearestCertifiedGoal (the same poses in the same order, tolerance 0), but a spot on
// no region also counts when off_regions(spot) holds: the first such pose, or nullopt.
std::optional<GoalPose> NearestGoalWith(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                        const GoalPose& goal, double max_shift_m, double max_turn_rad, double step_m,
                                        double yaw_step_rad, const std::function<bool(const Eigen::Vector2d&)>& off_regions,
                                        const Deadline& deadline = Deadline());

}  // namespace mfp
