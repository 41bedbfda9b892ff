#include "planner/planning/internal/window_problem.h"

#include <cmath>

#include "geometry/region_reachability.h"
#include "planner/planning/internal/window_body_regions.h"

namespace mfp {

std::optional<Eigen::Vector2d> LocalGoal(const PlanContext& context, const Eigen::Vector2d& centre,
                                         std::optional<double>* yaw_rad, double lookahead_scale) {
  const PlannerOptions& options = context.options;
  const RouteGuide& guide = context.guide;
  // Default: about one window's walk. A route over stance poses is followed closely (two
  // steps of d_lim per leg); one through region centres more loosely.
  const double lookahead = lookahead_scale * (options.local_goal_lookahead_m >= 0 ? options.local_goal_lookahead_m
                                              : guide.from_stances              ? 2.0 * context.robot.d_lim_m
                                                                                : 2.0 * LegReach(context.robot));
  if (!context.guided || !(lookahead > 0.0)) return std::nullopt;
  const double progress = RouteProgress(guide, centre);
  const double s = progress + lookahead;
  // Only where the route detours: where what is left of it is barely longer than the
  // straight line to the goal, the goal itself pulls the same way.
  const double straight_m = (context.GoalXY() - centre).norm();
  const bool detour = guide.length_m - progress > options.local_goal_detour_ratio * straight_m;
  const std::optional<double> route_yaw = RouteYaw(guide, s);
  if ((detour || route_yaw) && s < guide.length_m) {
    if (yaw_rad != nullptr) *yaw_rad = route_yaw;
    return RoutePoint(guide, s);
  }
  return std::nullopt;
}

FootstepProblem NextWindowProblem(const PlanContext& context, const HorizonState& state, int steps,
                                  double lookahead_scale, bool clear_of_body) {
  const int n = context.robot.num_legs();
  FootstepProblem problem = FirstWindowProblem(context.robot, context.regions, context.request, context.options);
  problem.start_feet_world_m = state.stance;
  problem.gait_phase = state.phase;
  problem.start_yaw_rad = state.yaw;
  problem.num_new_steps = steps;
  problem.regions.clear();
  for (int i : WindowRegionIndices(context.usable, state.stance, (steps + n - 1) / n, context.step_reach_m,
                                   context.robot.dz_max_m)) {
    problem.regions.push_back(context.usable[static_cast<size_t>(i)]);
  }
  std::optional<double> local_yaw;
  if (const std::optional<Eigen::Vector2d> local = LocalGoal(context, StanceCentreXY(state.stance), &local_yaw, lookahead_scale)) {
    problem.goal_x_m = local->x();
    problem.goal_y_m = local->y();
    // The route's yaw, unwrapped to the nearest turn from the stance's yaw.
    if (local_yaw) problem.goal_yaw_rad = state.yaw + std::remainder(*local_yaw - state.yaw, 2 * M_PI);
  }
  if (state.plan.windows > 0) {
    problem.history_feet_world_m = state.history;
    problem.start_step_yaw_rad = state.stance_yaw;
  }
  problem.body_regions = WindowBodyRegions(context, problem, clear_of_body);
  return problem;
}

void FinishGoalWeights(const PlanContext& context, FootstepProblem* problem) {
  const RobotModel& robot = context.robot;
  const double configuration_reward = robot.num_legs() * std::abs(robot.weights.trim_step);
  const double half_tolerance_m = 0.5 * context.goal.tolerance_m;
  const double half_yaw_tolerance_rad = 0.5 * context.goal.yaw_tolerance_rad;
  if (half_tolerance_m > 0.0) {
    problem->min_goal_position_weight = configuration_reward / (half_tolerance_m * half_tolerance_m);
  }
  if (half_yaw_tolerance_rad > 0.0) {
    problem->min_goal_yaw_weight = configuration_reward / (half_yaw_tolerance_rad * half_yaw_tolerance_rad);
  }
}

}  // namespace mfp
