#include "planner/planning/internal/goal_keeping.h"

#include <algorithm>
#include <cmath>

namespace mfp {
namespace {

// The window aims at the plan's goal (not a local goal along the route).
bool AimsAtGoal(const MiqpFormulation& formulation, const GoalSpec& goal) {
  return formulation.problem().goal_x_m == goal.x_m && formulation.problem().goal_y_m == goal.y_m;
}

// Half sides (on x, on y) of the largest-area box about the origin inside the disc of
// radius r that holds the offset d (|d| <= r).
Eigen::Vector2d HalfSidesHolding(const Eigen::Vector2d& d, double r) {
  const double square = r / std::sqrt(2.0);
  const double ax = std::abs(d.x()), ay = std::abs(d.y());
  if (ax <= square && ay <= square) return Eigen::Vector2d(square, square);
  if (ax > square) return Eigen::Vector2d(ax, std::sqrt(std::max(0.0, r * r - ax * ax)));
  return Eigen::Vector2d(std::sqrt(std::max(0.0, r * r - ay * ay)), ay);
}

}  // namespace

std::vector<VariableRange> GoalKeepingRanges(const MiqpFormulation& formulation, const GoalSpec& goal,
                                             const Eigen::VectorXd& x) {
  if (!AimsAtGoal(formulation, goal) || !(goal.tolerance_m > 0.0)) return {};
  const FootstepVariables& v = formulation.vars();
  const int n = formulation.num_legs();
  const int steps = formulation.num_steps();
  std::vector<VariableRange> ranges;
  for (int i = steps - n; i < steps; ++i) {
    const Eigen::Vector2d spot = formulation.GoalFoot(formulation.LegOfStep(i));
    const bool is_new = v.x[i] >= 0 && v.y[i] >= 0;
    const Eigen::Vector2d foot = is_new ? Eigen::Vector2d(x(v.x[i]), x(v.y[i]))
                                        : formulation.problem().start_feet_world_m[i].head<2>();
    const Eigen::Vector2d offset = foot - spot;
    if (offset.norm() > goal.tolerance_m) return {};
    if (!is_new) continue;
    const Eigen::Vector2d half = HalfSidesHolding(offset, goal.tolerance_m);
    ranges.push_back({v.x[i], spot.x() - half.x(), spot.x() + half.x()});
    ranges.push_back({v.y[i], spot.y() - half.y(), spot.y() + half.y()});
  }
  // The steps the plan takes stay taken: a plan that reaches the goal in fewer steps earns
  // their trim reward on the chords' reach, which the exact steps may not have.
  for (int i = n; i < steps; ++i) {
    if (v.trim[i] >= 0 && x(v.trim[i]) < 0.5) ranges.push_back({v.trim[i], 0.0, 0.0});
  }
  return ranges;
}

std::function<std::vector<VariableRange>(const Eigen::VectorXd&)> GoalKeeping(const MiqpFormulation& formulation,
                                                                              const GoalSpec& goal) {
  if (!AimsAtGoal(formulation, goal)) return nullptr;
  return [&formulation, goal](const Eigen::VectorXd& x) { return GoalKeepingRanges(formulation, goal, x); };
}

}  // namespace mfp
