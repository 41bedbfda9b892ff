#pragma once
// Removes the variables a branch-and-bound node has fixed (lower == upper, or within
// 1e-12 relative: fixed at the middle) from a QP,
// moving their contribution into the objective and the row bounds. Rows left without a
// free variable are checked directly. Solvers get a smaller problem, and none of them
// sees a constant row (Ipopt 3.11 returns a wrong "optimal" point on such rows).
#include <Eigen/Core>
#include <vector>

#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

struct ReducedQp {
  bool infeasible = false;        // a row cannot be met within the variable bounds
  Miqp problem;                   // over the free variables only (names left empty)
  Eigen::VectorXd lower, upper;   // bounds of the free variables
  std::vector<int> free_index;    // reduced variable -> original variable
  std::vector<int> row_index;     // reduced row -> original row
  Eigen::VectorXd fixed_x;        // original-size point holding the fixed values

  // The original-size point for a reduced solution.
  Eigen::VectorXd Expand(const Eigen::VectorXd& reduced_x) const;
  // The reduced part of an original-size point.
  Eigen::VectorXd Restrict(const Eigen::VectorXd& full_x) const;
};

ReducedQp ReduceFixedVariables(const Miqp& problem, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper, double row_tolerance);

// The first step of every relaxation backend: reduce, and settle the nodes that need no
// solver (crossed bounds, a row that cannot be met, nothing left free). Returns true when
// *result is final; otherwise *reduced is the QP to solve.
bool ReduceOrSettle(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                    double row_tolerance, ReducedQp* reduced, RelaxationResult* result);

}  // namespace mfp
