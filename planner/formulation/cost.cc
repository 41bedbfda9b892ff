#include "planner/formulation/internal/cost.h"

#include <algorithm>

namespace mfp {

Eigen::Vector2d GoalFoot(const FootstepProblem& problem, int leg) {
  return NominalFootXY(*problem.robot, leg, problem.goal_x_m, problem.goal_y_m, problem.goal_yaw_rad);
}

void AddCost(const StepExpressions& e, const FootstepProblem& problem, int num_steps, int num_configurations,
             const FootstepVariables& vars, MiqpBuilder* b) {
  const int n = e.num_legs();
  const int N = num_steps;
  const PlannerWeights& w = problem.robot->weights;
  const double goal_position = std::max(w.goal_position, problem.min_goal_position_weight);
  const double goal_yaw = std::max(w.goal_yaw, problem.min_goal_yaw_weight);
  for (int i = N - n; i < N; ++i) {
    const Eigen::Vector2d g = GoalFoot(problem, LegOfStep(problem, i));
    for (int axis = 0; axis < 2; ++axis) b->AddSquaredCost(e.Position(i, axis) - LinExpr::Constant(g(axis)), goal_position);
  }
  if (num_configurations > 1) b->AddSquaredCost(e.Yaw(num_configurations - 1) - LinExpr::Constant(problem.goal_yaw_rad), goal_yaw);
  for (int i = n; i < N; ++i) b->AddLinearCost(LinExpr::Var(vars.trim[i], w.trim_step));
  for (int i = n; i < N; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      b->AddSquaredCost(e.CentreOfContacts(i, axis) - e.CentreOfContacts(i - n, axis), w.displacement);
    }
  }
}

}  // namespace mfp
