#pragma once
// What every unit of one PlanFootsteps call reads and none changes: the robot, the map,
// the request, the options and the solvers; the limits derived from them (step budget,
// default window, time limit); the regions the start stance can reach; the route guide;
// and the plan's clock. Private to planner/planning.
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <optional>
#include <vector>

#include "planner/formulation/plan.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/goal.h"
#include "planner/planning/internal/route_guide.h"
#include "planner/robot/body_obstacle_index.h"

namespace mfp {

using PlanClock = std::chrono::steady_clock;

// Seconds of wall time since `start`.
double SecondsSince(PlanClock::time_point start);

struct PlanContext {
  // The plan's clock starts here.
  PlanContext(const RobotModel& robot_, const std::vector<ConvexRegion>& regions_, const PlanRequest& request_,
              const PlannerOptions& options_, const std::vector<RelaxationSolver*>& solvers_)
      : robot(robot_), regions(regions_), request(request_), options(options_), solvers(solvers_),
        start_time(PlanClock::now()) {
    if (robot.body.known() && !request.body_obstacles.empty()) {
      body_index = BodyObstacleIndex(request.body_obstacles, std::max(BodyRadius(robot.body), kBodyBucketMinM));
    }
  }

  const RobotModel& robot;
  const std::vector<ConvexRegion>& regions;
  const PlanRequest& request;
  const PlannerOptions& options;
  const std::vector<RelaxationSolver*>& solvers;
  PlanClock::time_point start_time;
  // The request's body obstacles by plan bucket (empty without a known body or obstacles).
  BodyObstacleIndex body_index;

  // Set by SetUpPlan.
  int max_steps = 0;           // new footsteps in the whole plan
  int window_steps = 0;        // new footsteps of a default window
  double time_limit_s = 0.0;   // the whole plan's
  double step_reach_m = 0.0;   // largest horizontal move of one foot in one step
  std::vector<ConvexRegion> usable;  // the regions the start stance can reach
  bool guided = false;         // route guidance on (whole plans only)
  RouteGuide guide;            // the route, when guided
  GoalSpec goal;

  double ElapsedSeconds() const { return SecondsSince(start_time); }
  // The plan's own time limit left [s] (may be negative).
  double TimeLeftSeconds() const { return time_limit_s - ElapsedSeconds(); }
  // The sooner of that and the caller's deadline [s].
  double RemainingSeconds() const;
  Eigen::Vector2d GoalXY() const { return {request.goal_x_m, request.goal_y_m}; }
};

// For a request that has passed CheckPlanRequest (PlanFootsteps checks it once): keeps
// the regions the start can reach and, under route guidance, plans the route and sets the
// step budget from its length. nullopt when the windows may start; else the plan that
// ends the request (no route, out of time).
std::optional<Plan> SetUpPlan(PlanContext* context);

}  // namespace mfp
