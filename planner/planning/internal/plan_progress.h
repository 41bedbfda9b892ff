#pragma once
// How much of its way a plan has left, the one measure by which the horizon judges
// progress (HorizonState::NoteProgress) and a plan that ends short of the goal keeps its
// best point. Private to planner/planning.
#include <Eigen/Core>
#include <vector>

#include "planner/formulation/plan.h"
#include "planner/planning/internal/plan_context.h"

namespace mfp {

// Arc length of the route left from the route point nearest to a body pose [m]. When the
// route carries yaws (RouteGuide::yaws_rad) the route is a curve in (x, y, rho yaw), with
// rho = metres_per_radian, so that turning on the spot toward the route's next heading
// is progress too; else the plan-view route.
double RouteLeft(const RouteGuide& guide, const Eigen::Vector2d& centre, double yaw_rad, double metres_per_radian);

// The way a footstep list's final stance (its last n footsteps) has left [m]: the larger of
// the route left (guided; else the straight line from the stance's centre to the goal) and
// how far the stance is from the goal (its worst foot from its goal spot, its yaw error
// in metres at d_lim per max_yaw_change), so that settling the feet on the goal at the
// route's end counts as progress.
double RemainingWay(const PlanContext& context, const std::vector<Footstep>& footsteps);

// Least decrease of RemainingWay that counts as progress [m]: a tenth of d_lim, at most
// half the goal tolerance.
double MinProgressGain(const PlanContext& context);

}  // namespace mfp
