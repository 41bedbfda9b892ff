#pragma once
// Goal footholds on seen floor. The regions are inset and cut around sensor noise, and on a
// real scan they can leave out flat floor a sensor saw well: a goal whose every stance
// within the goal tolerances has a spot there would be invalid_goal although a robot could
// stand at it. Such a spot, when a disk of the foot radius, a margin and one map cell
// around it is seen surface flat within a cell (FlatSeenDisk: issue 25's certifiable
// floor), gets a square region of its own, a foothold, and the plan goes to that stance.
// The way to the goal stays on the regions, but for start feet on no region (StartFootholds).
#include <optional>
#include <vector>

#include "base/deadline.h"
#include "geometry/convex_region.h"
#include "geometry/seen_surface.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/goal.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct FootholdGoal {
  GoalPose pose;                         // the stance planned to
  std::vector<int> legs;                 // the legs whose spots stand on footholds, in leg order
  std::vector<Eigen::Vector2d> spots_m;  // each such leg's goal spot, its foothold's centre [m, world]
  std::vector<ConvexRegion> footholds;   // one per such leg, ids above every region's
};

// The smallest region id above every id of `regions` and at least `at_least`: the first id
// a foothold added beside them may take.
int NextRegionId(const std::vector<ConvexRegion>& regions, int at_least = 0);

// The foothold square's first half side (goal_search.foothold_half_side; 0: half the goal
// tolerance, so a foot within the goal tolerance of its spot stays on it) and the largest
// it may grow to (goal_search.foothold_max_half_side; 0: the robot's d_lim) [m].
double FootholdHalfSide(const PlannerOptions& options);
double FootholdMaxHalfSide(const RobotModel& robot, const PlannerOptions& options);

// The foothold of a spot: a horizontal square about it, at the middle of the seen disk's
// tops, its plane half a cell thick, where the seen surface holds a flat disk of radius
// foot_radius_m + margin_m + the square's half diagonal (+ one cell) about the spot. Its
// half side is half_side_m, doubled while the disk stays flat and it stays within
// max_half_side_m (a larger foothold also holds the steps up to the goal stance);
// nullopt when half_side_m is not certified. With refuse_runs, a first square whose disk's
// two levels hold a run (a one-voxel riser, curb or groove at the spot: FlatSeenDisk) is not
// certified; the larger squares keep the two-level test.
std::optional<ConvexRegion> SeenFoothold(const SeenSurface& seen, const Eigen::Vector2d& spot, double foot_radius_m,
                                         double margin_m, double half_side_m, double max_half_side_m, int id,
                                         bool refuse_runs = true);

// The stance nearest to `goal` within goal_position_tolerance_m and goal_heading_tolerance_rad
// (NearestGoalWith's grid and order) whose every spot lies on a region or has a foothold,
// with those footholds (half side from FootholdHalfSide up to FootholdMaxHalfSide);
// nullopt when there is none, when the options turn
// footholds off, or when the deadline expires first.
std::optional<FootholdGoal> SeenFootholdGoal(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                             const SeenSurface& seen, const GoalPose& goal,
                                             const PlannerOptions& options, const Deadline& deadline);

// Footholds under the start feet that stand on no region (within start_tolerance_m) but on
// flat seen floor (SeenFoothold about each such foot, ids from first_id): the first steps may
// stand there too instead of having to reach a region in one step. The foot stands there (a
// fact, not a choice), so the disk keeps the two-level test without refusing runs (refusing
// them lost a real-scan walk whose start foot stood in a one-voxel groove: docs/measurements.md). Empty when the options
// turn them off or the request carries no seen surface.
std::vector<ConvexRegion> StartFootholds(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                         const PlanRequest& request, const PlannerOptions& options, int first_id);

}  // namespace mfp
