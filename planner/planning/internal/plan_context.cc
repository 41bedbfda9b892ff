#include "planner/planning/internal/plan_context.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "base/check.h"
#include "geometry/region_reachability.h"
#include "planner/planning/internal/plan_outcome.h"
#include "planner/planning/request_check.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {
namespace {

// Largest horizontal move of one foot in one step [m]: on each axis d_lim about the
// previous nominal spot plus how far the previous foot may lie from that spot (l_bnd, or
// the start stance's own offset, whichever is larger), as a Euclidean length; for the
// footprint shape, as MaxMovesXY (step_limits.h) bounds it.
double StepReachXY(const RobotModel& robot, const PlanRequest& request) {
  const int n = robot.num_legs();
  const Eigen::Vector2d centre = StanceCentreXY(request.start_feet_world_m);
  double offset = robot.l_bnd_m;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d d = request.start_feet_world_m[k].head<2>() -
                              NominalFootXY(robot, k, centre.x(), centre.y(), request.start_yaw_rad);
    offset = std::max(offset, d.cwiseAbs().maxCoeff());
  }
  if (robot.reach_shape == ReachShape::kFootprint) {
    // A leg's first move from the start (MaxMovesXY), or a later one within its polygon's
    // diameter.
    double move = 0.0;
    for (const LegModel& leg : robot.legs) {
      move = std::max({move, FootprintFarthestCorner(leg) + std::sqrt(2.0) * offset, FootprintDiameter(leg)});
    }
    return move;
  }
  return std::sqrt(2.0) * (robot.d_lim_m + offset);
}

// The plan ended, status time_limit, by its deadline or stop flag while `stage` ran.
Plan OutOfTime(const PlanContext& c, const std::string& stage) {
  Plan ended = Rejected(SolveStatus::kTimeLimit, std::string(c.request.deadline.Stopped() ? "stopped" : "time limit reached") +
                                                     " while " + stage + " (" + std::to_string(c.regions.size()) +
                                                     " regions)");
  ended.solve_time_s = c.ElapsedSeconds();
  return ended;
}

// Route guidance: 'no route', or a body route that sets the step budget.
std::optional<Plan> GuideRoute(PlanContext* c) {
  const PlanRequest& request = c->request;
  const PlannerOptions& options = c->options;
  // The plan's own time limit and the caller's deadline (and stop flag) bound the route
  // searches as they bound the windows: a large map must not hold the plan here.
  const Deadline deadline = request.deadline.Within(c->TimeLeftSeconds());
  c->guide = PlanRoute(c->robot, c->regions, request.start_feet_world_m, c->GoalXY(), request.goal_yaw_rad,
                       options.goal_tolerance_m, options.start_tolerance_m, deadline);
  if (c->guide.out_of_time) return OutOfTime(*c, "the region graph's route was searched");
  if (!c->guide.connected) {
    Plan rejected = Rejected(SolveStatus::kNoRoute, c->guide.broken);
    rejected.solve_time_s = c->ElapsedSeconds();
    return rejected;
  }
  // A route whose start feet each have a region one step away may still not start:
  // windows of at least one step per leg take every leg's first step from the start
  // stance, and a leg whose first step meets no region makes every window infeasible.
  const std::string broken =
      c->window_steps >= c->robot.num_legs()
          ? FirstStepWithoutRegion(c->robot, c->regions, request.start_feet_world_m, request.start_yaw_rad,
                                   options.start_tolerance_m)
          : "";
  if (!broken.empty()) {
    Plan rejected = Rejected(SolveStatus::kNoRoute, broken);
    rejected.solve_time_s = c->ElapsedSeconds();
    return rejected;
  }
  if (options.stance_route) {
    // Out of time here, the windows end the plan on its time limit at their first check.
    FollowStanceRoute(c->robot, c->usable, request.body_obstacles, request.start_feet_world_m, request.start_yaw_rad,
                      c->GoalXY(), request.goal_yaw_rad, options.stance_search, &c->guide, deadline);
    if (!c->guide.connected) {  // the body blocks every route the feet have
      Plan rejected = Rejected(SolveStatus::kNoRoute, c->guide.broken);
      rejected.solve_time_s = c->ElapsedSeconds();
      return rejected;
    }
  }
  if (request.max_steps == 0 && options.default_max_steps == 0) {
    // Enough configurations to walk the route route_step_budget times over at d_lim
    // per configuration; the time limit bounds the work.
    const int configurations =
        static_cast<int>(std::ceil(options.route_step_budget * c->guide.length_m / c->robot.d_lim_m)) + 4;
    c->max_steps = std::min(100000, std::max(c->max_steps, configurations * c->robot.num_legs()));
  }
  return std::nullopt;
}

}  // namespace

double SecondsSince(PlanClock::time_point start) {
  return std::chrono::duration<double>(PlanClock::now() - start).count();
}

double PlanContext::RemainingSeconds() const {
  return std::min(TimeLeftSeconds(), request.deadline.RemainingSeconds());
}

std::optional<Plan> SetUpPlan(PlanContext* c) {
  const RobotModel& robot = c->robot;
  const PlanRequest& request = c->request;
  const PlannerOptions& options = c->options;
  const int n = robot.num_legs();
  MFP_CHECK(n >= 2 && static_cast<int>(robot.gait.size()) == n);

  c->max_steps = MaxSteps(robot, request, options);
  c->window_steps = WindowSteps(robot, request, options);
  c->time_limit_s = request.time_limit_s > 0 ? request.time_limit_s : options.default_time_limit_s;
  c->goal = GoalSpec{request.goal_x_m, request.goal_y_m, request.goal_yaw_rad, options.goal_tolerance_m,
                     options.goal_yaw_tolerance_rad};

  // Only regions the start stance can reach (chains of steps within dz_max) enter the
  // MIQPs, and each window sees only those its steps can reach.
  c->step_reach_m = StepReachXY(robot, request);
  const std::optional<std::vector<int>> reachable =
      ReachableRegionIndices(c->regions, request.start_feet_world_m, c->step_reach_m, robot.dz_max_m,
                             options.start_tolerance_m, request.deadline.Within(c->TimeLeftSeconds()));
  if (!reachable) return OutOfTime(*c, "the regions the start stance can reach were found");
  for (int i : *reachable) c->usable.push_back(c->regions[static_cast<size_t>(i)]);
  c->guided = options.route_guidance && request.max_windows == 0;
  if (c->guided) return GuideRoute(c);
  return std::nullopt;
}

}  // namespace mfp
