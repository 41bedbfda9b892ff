#pragma once
// A body route from a search over stance poses, for the windows' local goals. The region
// graph (route_guide.h) proves that a route exists or not, foot by foot; it does not see
// that all n feet must stand at once, and its route through region centres cuts corners a
// whole body cannot (the wall detour: feet left hanging over a dead-end pocket). Here a
// body pose (x, y on a grid, yaw one of a few headings) is usable when every leg's
// nominal foot lies within l_bnd of some region, i.e. the leg's reference box meets
// support; A* over usable poses (moves to the 8 neighbouring cells, or a turn by one
// heading) gives a route the windows can follow, dearer through poses where a nominal
// foot is off every region. Heights are not judged here (the region graph and the MIQP
// do that). With body obstacles (body_clearance.h) and a known body box, a pose is also
// unusable when the body's plan box at the pose's yaw overlaps an obstacle in the body's
// height band above the pose's ground (the mean height of the regions under its nominal
// feet): the route keeps the body clear and turns where a passage fits only one way.
// No I/O.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "base/deadline.h"
#include "geometry/convex_region.h"
#include "planner/robot/body_clearance.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct StanceRouteOptions {
  double cell_m = 0.04;           // body grid; grown on large maps to stay within max_cells
  int headings = 8;               // yaw candidates, evenly spaced over a full turn
  // Where the body check refused poses, the search is run again with this many headings
  // (when more than `headings`), so the body can turn to fit a passage.
  int fine_headings = 16;
  int max_cells = 300000;         // body grid cells (x, y) at most
  // Before a route is refused for the body (route_guide.h), the search runs once more on
  // a grid of this cell when it is finer than cell_m: a passage a few centimetres wider
  // than the body can fall between the cells of the coarser grid [m].
  double body_blocked_cell_m = 0.02;
  double turn_cost_m = 0.05;      // cost of turning by one heading, as distance [m]
  // The windows hold the route's yaws (not the goal's heading) when at least this share of
  // the route's poses cannot be held at the goal's heading (route_guide.h).
  double route_yaw_unusable_share = 0.05;
  // Cost factor of moving through a pose where some nominal foot is off every region
  // (only its reference box meets one): the route keeps room where it can.
  double tight_cost_factor = 3.0;
  // A pose is usable when each leg's nominal foot has a region within this many l_bnd:
  // 1, the reference box's inscribed disk (the box surely meets the region); sqrt(2), its
  // corners (the box may meet it).
  double support_radius_l_bnd = 1.0;
  // Share of the body's plan box an obstacle may cover before a pose is unusable (room
  // for the grid's rounding; the checker's tolerance is larger).
  double body_overlap_share = 0.0;
  // Room the route keeps between the body's plan box and obstacles where it can [m]: a
  // pose whose box grown by this overlaps one costs tight_cost_factor (the windows' steps
  // between route poses cut corners; a route along a wall leaves them none).
  double body_margin_m = 0.04;
};

struct StanceRoute {
  bool found = false;
  bool out_of_time = false;  // the deadline passed (or its stop flag was set) first
  std::vector<Eigen::Vector2d> route;  // body positions from start to goal [m, world]
  std::vector<double> yaws_rad;        // body yaw at each route point [rad]
  double length_m = 0.0;
  long body_blocked_poses = 0;  // poses the search met that only the body check refused
  // Of those, the position of the one nearest the goal (NaN when none) [m, world]: where
  // a message says the body is blocked.
  Eigen::Vector2d body_blocked_nearest_goal_m = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Route poses (start and goal cells aside) not usable at the goal's heading: there the
  // body must hold the route's own yaw (a long, narrow stance crabbing along a field's
  // edge at the goal's yaw has feet off it).
  long goal_yaw_unusable_poses = 0;
  long classified_poses = 0;    // poses judged usable or not (each once)
  long expanded_poses = 0;      // poses expanded by the A* (each at most once)
};

// start and goal poses: body position [m] and yaw [rad]; they count as usable whatever the
// support around them (the start stance may be off nominal). The deadline is checked
// while the support raster is built and every few hundred A* expansions: past it the
// search ends with out_of_time set and no route.
StanceRoute PlanStanceRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                            const Eigen::Vector2d& start_xy, double start_yaw_rad, const Eigen::Vector2d& goal_xy,
                            double goal_yaw_rad, const StanceRouteOptions& options = {},
                            const Deadline& deadline = {});
// The same, keeping the body clear of `body_obstacles`. ground_z_m: the ground height
// assumed where no region lies under a pose's feet (the start stance's) [m].
StanceRoute PlanStanceRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                            const std::vector<BodyObstacle>& body_obstacles, double ground_z_m,
                            const Eigen::Vector2d& start_xy, double start_yaw_rad, const Eigen::Vector2d& goal_xy,
                            double goal_yaw_rad, const StanceRouteOptions& options = {},
                            const Deadline& deadline = {});
// The same, with the fallbacks a planner wants before it calls a route missing: where no
// route is found (and time is left), poses whose reference boxes may meet support
// (support_radius_l_bnd at least sqrt(2)); then, where the body check refused poses, the
// finer grid options.body_blocked_cell_m, taken if it finds a route or runs out of time.
StanceRoute PlanStanceRouteWithFallbacks(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                         const std::vector<BodyObstacle>& body_obstacles, double ground_z_m,
                                         const Eigen::Vector2d& start_xy, double start_yaw_rad,
                                         const Eigen::Vector2d& goal_xy, double goal_yaw_rad,
                                         const StanceRouteOptions& options, const Deadline& deadline);

}  // namespace mfp
