#pragma once
// Interface to a solver of the continuous relaxation of a Miqp (integrality dropped,
// variable bounds replaced by the branch-and-bound node's). Implementations are final
// classes in their own adapter files (Ipopt: ipopt_relaxation_solver.h).
#include <Eigen/Core>
#include <string>

#include "planner/base/deadline.h"
#include "planner/miqp/miqp.h"

namespace mfp {

enum class RelaxationStatus {
  kSolved,          // converged to the tolerance: x is optimal for the relaxation
  kInfeasible,      // the relaxation has no feasible point
  kIterationLimit,  // stopped early; x may be inaccurate
  kCutoff,          // stopped early on SetCutoff: objective is a proven floor of the
                    // relaxation's optimum at or above the cutoff; x is not optimal
  kFailed,          // numerical failure
};

struct RelaxationResult {
  RelaxationStatus status = RelaxationStatus::kFailed;
  Eigen::VectorXd x;
  double objective = 0.0;  // 0.5 x'Qx + c'x + constant at x
  int iterations = 0;
  // Optional, from the duals of the variable bounds (reduced costs): every point of the
  // node's box that meets the rows costs at least
  //   cost_floor + sum_j lower_cost_rate(j) (x_j - lower_j) + upper_cost_rate(j) (upper_j - x_j),
  // with cost_floor <= objective and the rates >= 0. The branch-and-bound uses it to
  // rule out integer values that cannot beat the incumbent. Empty rates: not given.
  double cost_floor = -kInfinity;
  Eigen::VectorXd lower_cost_rate, upper_cost_rate;
};

class RelaxationSolver {
 public:
  virtual ~RelaxationSolver() = default;
  // lower/upper replace problem.var_lower/var_upper (same size). warm_start may be null.
  virtual RelaxationResult Solve(const Miqp& problem, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper,
                                 const Eigen::VectorXd* warm_start) = 0;
  // Caps the time of the next solves (the branch-and-bound passes its remaining time).
  virtual void SetTimeLimit(double seconds) = 0;
  // The next solves stop, with status kIterationLimit, at their first check (every
  // iteration) after the deadline passes or its stop flag is set: a time limit holds
  // inside one solve, not only between solves. Solvers that cannot check ignore it.
  virtual void SetDeadline(const Deadline& /*deadline*/) {}
  // For the next Solve only: it may stop, with status kCutoff, once it proves that the
  // relaxation's optimum is at least this objective (a node that cannot beat the
  // incumbent need not be solved to the end). Solvers that cannot prove it ignore it.
  virtual void SetCutoff(double /*objective*/) {}
  // For the next Solve only: the relative accuracy asked of it, when looser than the
  // solver's own (a search that only needs bounds to a coarse gap need not pay for
  // digits it will not use). Solvers without such a setting ignore it.
  virtual void SetRelativeTolerance(double /*tolerance*/) {}
  virtual std::string Name() const = 0;
};

}  // namespace mfp
