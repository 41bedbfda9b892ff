#pragma once
// "Fix the integers and solve the QP": the completion of an integer assignment into a
// feasible point of a Miqp. Every heuristic that proposes integer values (the
// branch-and-bound's rounding, relax-and-fix's completion, the warm start from a previous
// plan) turns them into a plan through this one routine.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

// The relaxation of problem with every integer variable fixed to assignment's value
// (rounded, and clamped to its bounds): the convex QP left in the continuous variables.
// request's bounds are replaced; its warm start, deadline, cutoff and tolerance are used
// as given. When solved, the integer entries of x hold the fixed values exactly.
RelaxationResult SolveWithIntegersFixed(const Miqp& problem, const Eigen::VectorXd& assignment,
                                        RelaxationSolver& solver, RelaxationRequest request);

// The integers of x rounded, then x judged as a plan: its objective when it meets the
// rows and bounds within feasibility_tolerance, nullopt otherwise.
std::optional<double> FeasibleObjective(const Miqp& problem, Eigen::VectorXd* x, double feasibility_tolerance);

struct FixedAssignmentOptions {
  double feasibility_tolerance = 1e-5;  // rows and bounds violation accepted in a plan
  // Optional: a plan that meets the rows but that the caller refuses (x has its integers
  // rounded).
  std::function<bool(const Eigen::VectorXd& x)> acceptable;
  // Each QP also ends this many seconds after its start (besides the request's deadline).
  double max_solve_s = kInfinity;
};

// The best plan (least objective, the first one on ties) among the completions of
// assignments, solved one after the other with request (its bounds replaced).
// *solves (optional) counts the QPs solved, *fallbacks (optional) those the solver's
// fallback solved.
std::optional<Eigen::VectorXd> BestFixedAssignment(const Miqp& problem, const std::vector<Eigen::VectorXd>& assignments,
                                                   RelaxationSolver& solver, const RelaxationRequest& request,
                                                   const FixedAssignmentOptions& options, int* solves = nullptr,
                                                   int* fallbacks = nullptr);

}  // namespace mfp
