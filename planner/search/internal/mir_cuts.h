#pragma once
// Complemented mixed-integer rounding (c-MIR) cuts for a Miqp, separated against a
// relaxation point (Marchand and Wolsey's aggregation heuristic): a base inequality is a
// row, or a row plus nonnegative multiples of up to max_aggregations other rows chosen to
// cancel continuous variables that lie strictly inside their bounds at the point (the
// region big-M rows with the rows that tie the same foot position, for instance). Each
// base inequality's variables are shifted to their nearer bound (integers complemented),
// divided by a divisor taken from its integer coefficients, and rounded. A continuous
// variable may be shifted to a variable bound (a two-variable row with a binary, such as
// a region's big-M row on one coordinate) instead of a simple bound, and a one-of group's
// equality may be added to cancel the group's largest coefficient: the base inequalities
// from which repeated rounds derive the hull-like bounds of the region disjunctions.
//
// Validity: a cut holds for every point that meets the problem's rows, the bounds given
// (which must be valid for every integer-feasible point: the problem's own, or those of
// bound propagation at the root) and integrality. Integers must have finite bounds and
// continuous variables a finite bound on the side the base inequality needs, else that
// base inequality gives no cut.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "planner/miqp/miqp.h"

namespace mfp {

// sum_k coefficients[k].second * x(coefficients[k].first) <= rhs, sorted by variable and
// scaled so that the largest |coefficient| is 1.
struct LinearCut {
  std::vector<std::pair<int, double>> coefficients;
  double rhs = 0.0;
  double efficacy = 0.0;  // violation at the separated point / Euclidean norm of the coefficients

  double Activity(const Eigen::VectorXd& x) const;
};

struct MirSeparationOptions {
  int max_aggregations = 3;        // rows added to a starting row to cancel continuous variables
  double min_efficacy = 1e-4;      // violation per unit coefficient norm (units of x) for a cut to count
  double max_coefficient_ratio = 1e6;  // largest/smallest |coefficient| allowed in a cut
  // A continuous variable is cancelled by aggregation only when it lies farther than
  // this from both bounds (in its own units).
  double min_bound_distance = 1e-6;
  // A row joins an aggregation only when its slack at the point is at most this.
  double max_aggregation_slack = 1e-4;
};

// Violated c-MIR cuts at x (one per starting row and side at most), most efficacious
// first. lower/upper: the bounds in force (see the header comment).
std::vector<LinearCut> SeparateMirCuts(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                       const Eigen::VectorXd& x, const MirSeparationOptions& options);

// Group bound cuts: for a continuous x_j with variable upper bounds x_j <= u_r when z_r = 1
// read off two-variable rows (a region's big-M row on one coordinate) for binaries z_r of
// one one-of group, and upper bound U on x_j,
//   x_j <= U - sum_r (U - u_r) z_r,
// (and the mirror for lower bounds): valid because at most one z_r is 1, and the convex
// hull's bound where the big-M rows give x_j <= u_r + M_r (1 - z_r) separately. Violated
// ones at x, most efficacious first.
std::vector<LinearCut> SeparateGroupBoundCuts(const Miqp& problem, const Eigen::VectorXd& lower,
                                              const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                                              double min_efficacy);

}  // namespace mfp
