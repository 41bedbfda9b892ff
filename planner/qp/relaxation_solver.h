#pragma once
// Interface to a solver of the continuous relaxation of a Miqp (integrality dropped,
// variable bounds replaced by the branch-and-bound node's). Implementations are final
// classes in their own adapter files (Ipopt: ipopt_relaxation_solver.h).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"

namespace mfp {

// A solver's opaque hint from one solve for a related later one (a branch-and-bound
// node's result for its children): immutable, shared, small (an index list, never
// factors). What it holds is the solver's business (the dual active set: its active
// constraints); solvers that keep none leave it null and ignore it.
using WarmStartToken = std::shared_ptr<const std::vector<int>>;

enum class RelaxationStatus {
  kSolved,          // converged to the tolerance: x is optimal for the relaxation
  kInfeasible,      // the relaxation has no feasible point
  kIterationLimit,  // stopped early; x may be inaccurate
  kCutoff,          // stopped early on RelaxationRequest::cutoff: objective is a proven
                    // floor of the relaxation's optimum at or above the cutoff; x is not optimal
  kFailed,          // numerical failure
};

struct RelaxationResult {
  RelaxationStatus status = RelaxationStatus::kFailed;
  Eigen::VectorXd x;
  double objective = 0.0;  // 0.5 x'Qx + c'x + constant at x
  // The solver's own steps, a work count for statistics only: interior-point iterations,
  // dual active-set steps, or (a solver that falls back from one method to another) their sum.
  int iterations = 0;
  // Optional, from the duals of the variable bounds (reduced costs): every point of the
  // node's box that meets the rows costs at least
  //   cost_floor + sum_j lower_cost_rate(j) (x_j - lower_j) + upper_cost_rate(j) (upper_j - x_j),
  // with cost_floor <= objective and the rates >= 0. The branch-and-bound uses it to
  // rule out integer values that cannot beat the incumbent. Empty rates: not given.
  double cost_floor = -kInfinity;
  Eigen::VectorXd lower_cost_rate, upper_cost_rate;
  // Optional: a floor of the relaxation's optimum proven without rates, at least
  // cost_floor and at most objective (for bounds only). -infinity: not given.
  double bound_floor = -kInfinity;
  // What a solved relaxation proves of its optimum, the bound a search may use: the
  // higher of cost_floor and bound_floor when given; else the objective of a solver that
  // certifies nothing (Ipopt), trusted to its tolerance. (The search reads it of solved
  // results only: a kCutoff result's objective is already a floor by its contract.)
  double CertifiedFloor() const {
    const double floor = std::max(cost_floor, bound_floor);
    return std::isfinite(floor) ? floor : objective;
  }
  // Optional, with the rates above: the multipliers (>= 0) of each row's lower and upper
  // side at x, for seeding an active-set solver. Empty: not given.
  Eigen::VectorXd row_lower_rate, row_upper_rate;
  // kFailed because the problem exceeds the solver's work budget (it was not attempted):
  // no other solver is tried on it either, as none finishes such a problem in a plan's time.
  bool over_work_budget = false;
  // For a later related solve (RelaxationRequest::warm_token); null: none.
  WarmStartToken warm_token;
  // Statistics of a backend that hands what its primary solver cannot finish to a
  // fallback (relaxation_solver_factory.h): 1 when this result is the fallback's, with
  // the wall time of both attempts [s]; 0 otherwise.
  int fallbacks = 0;
  double fallback_time_s = 0.0;
  // Statistics of a crossover (RelaxationRequest::polish_tolerance): the active sets
  // tried, and 1 when this result is a polished one (its floor certified by the polished
  // point's multipliers); 0 without one.
  int polish_attempts = 0;
  int polished = 0;
};

// One solve's whole contract, as Drake's Solve(program, initial_guess, options): a
// solver keeps nothing from one request to the next.
struct RelaxationRequest {
  // The variable bounds in force (a branch-and-bound node's); they replace
  // problem.var_lower/var_upper. Empty: the problem's own.
  Eigen::VectorXd lower, upper;
  // A point to start from (the parent node's relaxation point). Empty: a cold start.
  Eigen::VectorXd warm_start;
  // The warm_token of a related solve (the parent node's); null: none.
  WarmStartToken warm_token;
  // The solve stops, with status kIterationLimit, at its first check (every iteration)
  // after the deadline passes or its stop flag is set: a time limit holds inside one
  // solve, not only between solves. Solvers that cannot check ignore it; solvers that cap
  // their own time (Ipopt's CPU time) cap it at what is left of it.
  Deadline deadline;
  // The solve may stop, with status kCutoff, once it proves that the relaxation's
  // optimum is at least this objective (a node that cannot beat the incumbent need not
  // be solved to the end). Infinite: solve to the end. Solvers that cannot prove it ignore it.
  double cutoff = kInfinity;
  // The relative accuracy asked of the solve, when looser than the solver's own (a
  // search that only needs bounds to a coarse gap need not pay for digits it will not
  // use); 0: the solver's own. Solvers without such a setting ignore it.
  double relative_tolerance = 0.0;
  // Crossover, off at 0: the solver may finish from its iterate's active set once its
  // relative residuals reach this (an exact optimum and a floor equal to it when the
  // guess is right; its own method on otherwise). Solvers without one ignore it.
  double polish_tolerance = 0.0;
  // Re-certification (BranchAndBoundOptions::recertify_leaves): the solve may spend
  // several times its usual work to bring its certified floor (RelaxationResult::
  // CertifiedFloor) up to its objective, by the exact methods it has (the crossover, an
  // active-set solve from its answer's active set). Solvers without one ignore it.
  bool certify_floor = false;

  // The bounds in force: lower/upper, or the problem's own when empty.
  const Eigen::VectorXd& LowerOr(const Miqp& problem) const { return lower.size() ? lower : problem.var_lower; }
  const Eigen::VectorXd& UpperOr(const Miqp& problem) const { return upper.size() ? upper : problem.var_upper; }
  // The warm start, or null for a cold start.
  const Eigen::VectorXd* WarmStart() const { return warm_start.size() ? &warm_start : nullptr; }
};

class RelaxationSolver {
 public:
  virtual ~RelaxationSolver() = default;
  // Solves the relaxation of problem under request (sizes: problem.num_variables()).
  // A solver object may not be used by two threads at once.
  virtual RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) = 0;
  virtual std::string Name() const = 0;
};

}  // namespace mfp
