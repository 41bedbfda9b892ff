#pragma once
// Route guidance before the receding windows: a graph over the safe regions whose edges
// are the steps a foot can make between them: two regions are joined when one move of the
// robot's step polygon (reach_polygon.h: the reach box or octagon of d_lim plus the
// reference box of l_bnd) bridges their gap, exactly what a window's rows allow, and their
// heights are within dz_max. Every plan moves each foot along a path of this graph, so when the
// graph does not connect a leg's start region to a region at its goal spot there is no
// plan at all: the planner answers 'no route' at once and names where the route breaks.
// Otherwise the shortest path over region centres is a body route: its length sets the
// step budget and its points the windows' local goals. No I/O.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "base/deadline.h"
#include "geometry/convex_region.h"
#include "planner/planning/internal/stance_route.h"
#include "planner/robot/body_clearance.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct RouteGuide {
  bool connected = false;
  // The deadline passed (or its stop flag was set) before the route was known: neither
  // a route nor a proof that there is none.
  bool out_of_time = false;
  std::string broken;  // when !connected and in time: where the route breaks, for the user
  // Body route in plan view from the start centre to the goal [m, world]; its polyline
  // passes through the centres of the regions a foot path crosses.
  std::vector<Eigen::Vector2d> route;
  double length_m = 0.0;
  bool from_stances = false;  // route from the stance search (FollowStanceRoute)
  // Body yaw at each route point, when the route keeps the body clear of obstacles and
  // the body check refused some pose (the yaw then matters); else empty [rad].
  std::vector<double> yaws_rad;
};

// Longest horizontal distance, in any direction, between two regions that one step can
// bridge: the step polygon's farthest corner (sqrt(2) (d_lim + l_bnd) for the box, on a
// diagonal; on a world axis a step moves at most d_lim + l_bnd) [m]. For seeds and
// messages; the graph's edges use the step polygon itself.
double MaxStepSpan(const RobotModel& robot);

// "" or, for the first start foot that no region holds (within start_tolerance_m) whose
// first step can land in no region, why: the MIQP puts a leg's first step in its reach
// polygon (d_lim on each axis) about that leg's nominal spot in the start stance (centre of the start feet,
// start yaw) and within dz_max of its start foot; no region meets that box. (The route
// graph's one-step span, MaxStepSpan, is the reach of later steps.) start_feet: leg order.
std::string FirstStepWithoutRegion(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                   const std::vector<Eigen::Vector3d>& start_feet, double start_yaw_rad,
                                   double start_tolerance_m);

// start_feet: leg order. start_tolerance_m: how far off its region a start foot may be.
// The deadline is checked per region while the graph is built and during its search.
RouteGuide PlanRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                     const std::vector<Eigen::Vector3d>& start_feet, const Eigen::Vector2d& goal_xy, double goal_yaw_rad,
                     double goal_tolerance_m, double start_tolerance_m, const Deadline& deadline = {});

// Replaces a connected guide's route by a route over stance poses (stance_route.h) from
// the start stance's centre and yaw to the goal, when that search finds one.
// start_feet: leg order. Past the deadline the guide keeps its route and out_of_time is set.
// body_obstacles: what the body keeps clear of (stance_route.h); may be empty.
void FollowStanceRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                       const std::vector<BodyObstacle>& body_obstacles,
                       const std::vector<Eigen::Vector3d>& start_feet, double start_yaw_rad,
                       const Eigen::Vector2d& goal_xy, double goal_yaw_rad, const StanceRouteOptions& options,
                       RouteGuide* guide, const Deadline& deadline = {});

// The point of the route at arc length s (clamped to the route) [m].
Eigen::Vector2d RoutePoint(const RouteGuide& guide, double s_m);
// The body yaw the route holds at arc length s: that of the route point the segment
// starts from; nullopt when the route carries no yaws [rad].
std::optional<double> RouteYaw(const RouteGuide& guide, double s_m);
// Arc length of the route point nearest to p [m].
double RouteProgress(const RouteGuide& guide, const Eigen::Vector2d& p);

}  // namespace mfp
