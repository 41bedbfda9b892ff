#include "planner/qp/fixed_integer_qp.h"

#include <algorithm>
#include <cmath>

namespace mfp {

RelaxationResult SolveWithIntegersFixed(const Miqp& problem, const Eigen::VectorXd& assignment,
                                        RelaxationSolver& solver, RelaxationRequest request) {
  request.lower = problem.var_lower;
  request.upper = problem.var_upper;
  for (int j = 0; j < problem.num_variables(); ++j) {
    if (!problem.is_integer[j]) continue;
    request.lower(j) = request.upper(j) =
        std::clamp(std::round(assignment(j)), problem.var_lower(j), problem.var_upper(j));
  }
  RelaxationResult result = solver.Solve(problem, request);
  if (result.status == RelaxationStatus::kSolved) {
    for (int j = 0; j < problem.num_variables(); ++j) {
      if (problem.is_integer[j]) result.x(j) = request.lower(j);
    }
  }
  return result;
}

std::optional<double> FeasibleObjective(const Miqp& problem, Eigen::VectorXd* x, double feasibility_tolerance) {
  for (int j = 0; j < problem.num_variables(); ++j) {
    if (problem.is_integer[j]) (*x)(j) = std::round((*x)(j));
  }
  if (problem.MaxViolation(*x) > feasibility_tolerance) return std::nullopt;
  return problem.Objective(*x);
}

std::optional<Eigen::VectorXd> BestFixedAssignment(const Miqp& problem, const std::vector<Eigen::VectorXd>& assignments,
                                                   RelaxationSolver& solver, const RelaxationRequest& request,
                                                   const FixedAssignmentOptions& options, int* solves,
                                                   int* fallbacks) {
  std::optional<Eigen::VectorXd> best;
  double best_objective = kInfinity;
  for (const Eigen::VectorXd& assignment : assignments) {
    RelaxationRequest one = request;
    if (options.max_solve_s < kInfinity) one.deadline = request.deadline.Within(options.max_solve_s);
    RelaxationResult r = SolveWithIntegersFixed(problem, assignment, solver, std::move(one));
    if (solves != nullptr) ++*solves;
    if (fallbacks != nullptr) *fallbacks += r.fallbacks;
    if (r.status != RelaxationStatus::kSolved) continue;
    const std::optional<double> objective = FeasibleObjective(problem, &r.x, options.feasibility_tolerance);
    if (!objective || (options.acceptable && !options.acceptable(r.x))) continue;
    if (*objective < best_objective) {
      best_objective = *objective;
      best = std::move(r.x);
    }
  }
  return best;
}

}  // namespace mfp
