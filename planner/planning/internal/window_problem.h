#pragma once
// The MIQP problem of the next receding window, and the local goal that makes its goal
// term follow the route. Private to planner/planning.
#include <Eigen/Core>
#include <optional>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"

namespace mfp {

// Under route guidance, the point of the route a lookahead ahead of the stance centre
// that the window's goal term pulls toward (PlannerOptions::local_goal_lookahead_m),
// while the route left detours (is longer than local_goal_detour_ratio times the straight
// line to the goal) and that point is short of the route's end. nullopt: the goal itself.
// A route that carries yaws (it keeps the body clear of obstacles) is followed to its end
// whatever its detour, and *yaw_rad (when given) receives its yaw at that point.
// lookahead_scale: the lookahead times this (a window re-planned closer to the route).
std::optional<Eigen::Vector2d> LocalGoal(const PlanContext& context, const Eigen::Vector2d& stance_centre,
                                         std::optional<double>* yaw_rad = nullptr, double lookahead_scale = 1.0);

// The window from the state's stance: `steps` new footsteps, the usable regions those
// steps can reach, the local goal, and after the first window the feet's history; its
// body regions (WindowBodyRegions) when formulation.body_regions is on or the window is
// planned again clear_of_body.
FootstepProblem NextWindowProblem(const PlanContext& context, const HorizonState& state, int steps,
                                  double lookahead_scale = 1.0, bool clear_of_body = false);

// Goal weights for a plan's finishing windows (HorizonPolicy::FinishAtGoal): a foot half
// the goal tolerance off its spot, or the yaw half its tolerance off, outweighs the trim
// reward of a whole configuration's steps (n |trim_step|), so that a window closes the
// last gap whichever leg it needs to move. Never below the robot's own weights.
void FinishGoalWeights(const PlanContext& context, FootstepProblem* problem);

}  // namespace mfp
