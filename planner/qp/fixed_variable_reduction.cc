#include "planner/qp/internal/fixed_variable_reduction.h"

#include <Eigen/SparseCore>
#include <algorithm>

#include "base/check.h"

namespace mfp {

Eigen::VectorXd ReducedQp::Expand(const Eigen::VectorXd& reduced_x) const {
  MFP_CHECK(reduced_x.size() == static_cast<Eigen::Index>(free_index.size()));
  Eigen::VectorXd x = fixed_x;
  for (size_t k = 0; k < free_index.size(); ++k) x(free_index[k]) = reduced_x(k);
  return x;
}

Eigen::VectorXd ReducedQp::Restrict(const Eigen::VectorXd& full_x) const {
  Eigen::VectorXd r(free_index.size());
  for (size_t k = 0; k < free_index.size(); ++k) r(k) = full_x(free_index[k]);
  return r;
}

namespace {
constexpr double kFixedWidth = 1e-12;  // relative to the bounds' magnitude
}  // namespace

ReducedQp ReduceFixedVariables(const Miqp& p, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper, double row_tolerance) {
  const int n = p.num_variables();
  MFP_CHECK(lower.size() == n && upper.size() == n);
  ReducedQp r;
  r.fixed_x = Eigen::VectorXd::Zero(n);
  std::vector<int> reduced_of(n, -1);
  for (int j = 0; j < n; ++j) {
    // A box narrower than rounding error (bound propagation leaves boxes of 1e-18 from
    // rows that pin a variable) is a fixed variable: kept free, its bound duals grow
    // without limit and the interior point never converges (then Ipopt solved it, at
    // 25 times the cost: 85 % of the plan time on generated stepping stones).
    const double width = kFixedWidth * (1.0 + std::max(std::abs(lower(j)), std::abs(upper(j))));
    if (lower(j) < upper(j) - width) {
      reduced_of[j] = static_cast<int>(r.free_index.size());
      r.free_index.push_back(j);
    } else {
      r.fixed_x(j) = lower(j) < upper(j) ? 0.5 * (lower(j) + upper(j)) : lower(j);
    }
  }
  const int nf = static_cast<int>(r.free_index.size());
  r.lower.resize(nf);
  r.upper.resize(nf);
  for (int k = 0; k < nf; ++k) {
    r.lower(k) = lower(r.free_index[k]);
    r.upper(k) = upper(r.free_index[k]);
  }
  // Objective: 0.5 xF'QFF xF + (cF + QFX v)' xF + (0.5 v'QXX v + cX'v + constant).
  const Eigen::VectorXd q_fixed = p.Q * r.fixed_x;
  Miqp& out = r.problem;
  out.constant = p.constant + 0.5 * r.fixed_x.dot(q_fixed) + p.c.dot(r.fixed_x);
  out.c.resize(nf);
  for (int k = 0; k < nf; ++k) out.c(k) = p.c(r.free_index[k]) + q_fixed(r.free_index[k]);
  // q_fixed includes the free columns' own diagonal products only through fixed_x,
  // which is zero on free variables, so no correction is needed.
  std::vector<Eigen::Triplet<double>> q_triplets;
  for (int col = 0; col < p.Q.outerSize(); ++col) {
    if (reduced_of[col] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.Q, col); it; ++it) {
      if (reduced_of[it.row()] >= 0) q_triplets.emplace_back(reduced_of[it.row()], reduced_of[col], it.value());
    }
  }
  out.Q.resize(nf, nf);
  out.Q.setFromTriplets(q_triplets.begin(), q_triplets.end());
  // Rows: keep those with a free variable, shifted by the fixed part.
  std::vector<Eigen::Triplet<double>> a_triplets;
  std::vector<double> row_lo, row_hi;
  for (int row = 0; row < p.A.outerSize(); ++row) {
    double shift = 0.0;
    bool has_free = false;
    // Range of the free part over the variable box: a row it cannot meet makes the node
    // infeasible without asking a solver (Ipopt can take hundreds of iterations to say so).
    double activity_min = 0.0, activity_max = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, row); it; ++it) {
      if (reduced_of[it.col()] >= 0) {
        has_free = true;
        const double a = it.value() * lower(it.col()), b = it.value() * upper(it.col());
        activity_min += std::min(a, b);
        activity_max += std::max(a, b);
      } else {
        shift += it.value() * r.fixed_x(it.col());
      }
    }
    double lo = p.row_lower(row) - shift, hi = p.row_upper(row) - shift;
    if (activity_max < lo - row_tolerance || activity_min > hi + row_tolerance) r.infeasible = true;
    if (!has_free) continue;
    // A side the variable box already keeps is left out, and a row with neither side
    // left is dropped: at deep nodes most big-M rows of the regions and chords a node has
    // ruled out are such rows, and the solvers get fewer inequalities.
    if (lo > -kInfinity && lo < hi && activity_min >= lo) lo = -kInfinity;
    if (hi < kInfinity && lo < hi && activity_max <= hi) hi = kInfinity;
    if (lo == -kInfinity && hi == kInfinity) continue;
    const int out_row = static_cast<int>(row_lo.size());
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, row); it; ++it) {
      if (reduced_of[it.col()] >= 0) a_triplets.emplace_back(out_row, reduced_of[it.col()], it.value());
    }
    row_lo.push_back(lo);
    row_hi.push_back(hi);
    r.row_index.push_back(row);
  }
  out.A.resize(static_cast<Eigen::Index>(row_lo.size()), nf);
  out.A.setFromTriplets(a_triplets.begin(), a_triplets.end());
  out.row_lower = Eigen::Map<const Eigen::VectorXd>(row_lo.data(), row_lo.size());
  out.row_upper = Eigen::Map<const Eigen::VectorXd>(row_hi.data(), row_hi.size());
  out.var_lower = r.lower;
  out.var_upper = r.upper;
  out.is_integer.assign(nf, false);
  for (int k = 0; k < nf; ++k) out.is_integer[k] = p.is_integer[r.free_index[k]];
  return r;
}

bool ReduceOrSettle(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                    double row_tolerance, ReducedQp* reduced, RelaxationResult* result) {
  MFP_CHECK(lower.size() == problem.num_variables() && upper.size() == problem.num_variables());
  *result = RelaxationResult();
  if ((lower.array() > upper.array()).any()) {
    result->status = RelaxationStatus::kInfeasible;
    return true;
  }
  *reduced = ReduceFixedVariables(problem, lower, upper, row_tolerance);
  if (reduced->infeasible) {
    result->status = RelaxationStatus::kInfeasible;
    return true;
  }
  if (reduced->free_index.empty()) {
    result->status = RelaxationStatus::kSolved;
    result->x = reduced->fixed_x;
    result->objective = problem.Objective(result->x);
    return true;
  }
  return false;
}

}  // namespace mfp
