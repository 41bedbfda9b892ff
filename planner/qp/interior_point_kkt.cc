#include "planner/qp/internal/interior_point_kkt.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "base/check.h"

namespace mfp {

InequalityForm BuildInequalityForm(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                   double penalty) {
  InequalityForm f;
  f.n = p.num_variables();
  // Rows: a'x - e <= u and -a'x - e <= -l, each with its own elastic variable.
  std::vector<std::pair<int, double>> row_sides;  // (row, sign)
  for (int i = 0; i < p.num_rows(); ++i) {
    if (std::isfinite(p.row_upper(i))) row_sides.emplace_back(i, 1.0);
    if (std::isfinite(p.row_lower(i))) row_sides.emplace_back(i, -1.0);
  }
  f.elastic = static_cast<int>(row_sides.size());
  const int E = f.elastic;
  std::vector<Eigen::Triplet<double>> g;
  f.d.resize(2 * E + 2 * f.n);
  for (int k = 0; k < E; ++k) {
    const auto [row, sign] = row_sides[k];
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, row); it; ++it) {
      g.emplace_back(k, static_cast<int>(it.col()), sign * it.value());
    }
    f.d(k) = sign > 0 ? p.row_upper(row) : -p.row_lower(row);
    f.d(E + k) = 0.0;  // e >= 0
  }
  for (int j = 0; j < f.n; ++j) {  // variable bounds
    MFP_CHECK(std::isfinite(lower(j)) && std::isfinite(upper(j)) && lower(j) < upper(j));
    f.d(2 * E + 2 * j) = upper(j);
    f.d(2 * E + 2 * j + 1) = -lower(j);
  }
  f.G.resize(E, f.n);
  f.G.setFromTriplets(g.begin(), g.end());
  f.Gt = f.G.transpose();
  f.Q = p.Q;
  f.q = Eigen::VectorXd::Zero(f.n + E);
  f.q.head(f.n) = p.c;
  f.q.tail(E).setConstant(penalty);
  return f;
}
namespace {

// A Newton system solved to this relative residual, as a multiple of the solve's
// tolerance, needs no refinement step: 1e-10 at the search's 1e-8, 1e-8 at
// relax-and-fix's stage accuracy of 1e-6, where refining further took a third more
// triangular solves and changed no iterate count or plan (docs/measurements.md).
constexpr double kRefinementPerTolerance = 0.01;

// An approximate minimum degree order of a symmetric pattern (lower triangle given).
std::vector<int> MinimumDegreeOrder(const SpMat& lower) {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(lower, amd);  // amd.indices()(k): the variable eliminated k-th
  return std::vector<int>(amd.indices().data(), amd.indices().data() + amd.indices().size());
}


}  // namespace

double KktProductTerms(const InequalityForm& f) {
  double terms = 0.0;
  for (int k = 0; k < f.Gt.outerSize(); ++k) {
    const double row = static_cast<double>(f.Gt.outerIndexPtr()[k + 1] - f.Gt.outerIndexPtr()[k]);
    terms += 0.5 * row * (row + 1.0);
  }
  return terms;
}

KktAssembly::KktAssembly(const InequalityForm& f, const Deadline& deadline) {
  const int n = f.n;
  // 1. The lower triangle of Q + G'G + I in the original order (compressed columns,
  //    sorted rows). entry_of[a] is row a's entry in the column being built.
  std::vector<int> lower_outer(n + 1, 0), lower_inner;
  std::vector<int> mark(n, -1), entry_of(n, -1);
  std::vector<std::pair<int, double>> q_entries;  // (entry, value)
  diagonal.resize(n);
  for (int col = 0; col < n; ++col) {
    if (col % 256 == 255 && deadline.Expired()) {
      interrupted = true;
      return;
    }
    const int begin = static_cast<int>(lower_inner.size());
    const auto touch = [&](int row) {
      if (mark[row] == col) return;
      mark[row] = col;
      lower_inner.push_back(row);
    };
    touch(col);
    for (SpMat::InnerIterator q(f.Q, col); q; ++q) {
      if (q.row() >= col) touch(static_cast<int>(q.row()));
    }
    const size_t first_term = terms.size();
    for (SpMat::InnerIterator g(f.G, col); g; ++g) {  // the elastic rows k holding col
      const int k = static_cast<int>(g.row());
      for (SpMat::InnerIterator a(f.Gt, k); a; ++a) {  // the variables of row k
        if (a.row() < col) continue;
        touch(static_cast<int>(a.row()));
        // index holds the term's row in this column until that row's entry is known
        terms.push_back({k, static_cast<int>(a.row()), a.value() * g.value()});
      }
    }
    std::sort(lower_inner.begin() + begin, lower_inner.end());
    for (int e = begin; e < static_cast<int>(lower_inner.size()); ++e) entry_of[lower_inner[e]] = e;
    diagonal[col] = entry_of[col];
    for (SpMat::InnerIterator q(f.Q, col); q; ++q) {
      if (q.row() >= col) q_entries.emplace_back(entry_of[q.row()], q.value());
    }
    for (size_t t = first_term; t < terms.size(); ++t) terms[t].index = entry_of[terms[t].index];
    lower_outer[col + 1] = static_cast<int>(lower_inner.size());
  }
  const int entries = lower_outer[n];
  // 2. The elimination order, per QP: one order for the whole MIQP, restricted to each
  //    node's free variables, had more fill-in, which cost more than the AMD
  //    (docs/measurements.md).
  const std::vector<double> ones(entries, 1.0);
  const Eigen::Map<const SpMat> lower(n, n, entries, lower_outer.data(), lower_inner.data(), ones.data());
  if (deadline.Expired()) {
    interrupted = true;
    return;
  }
  const std::vector<int> order = MinimumDegreeOrder(SpMat(lower));
  MFP_CHECK(static_cast<int>(order.size()) == n);
  position.assign(n, -1);
  for (int k = 0; k < n; ++k) {
    MFP_CHECK(order[k] >= 0 && order[k] < n && position[order[k]] < 0);
    position[order[k]] = k;
  }
  // 3. The permuted upper triangle: entry (a, b) goes to (min, max) of their positions;
  //    columns by counting, rows sorted within each. slot: an entry's value index there.
  std::vector<int> upper_outer(n + 1, 0), upper_inner(entries), slot(entries);
  std::vector<std::pair<int, int>> placed(entries);  // (row, entry) by column
  for (int b = 0; b < n; ++b) {
    for (int e = lower_outer[b]; e < lower_outer[b + 1]; ++e) {
      ++upper_outer[std::max(position[lower_inner[e]], position[b]) + 1];
    }
  }
  for (int c = 0; c < n; ++c) upper_outer[c + 1] += upper_outer[c];
  std::vector<int> fill(upper_outer.begin(), upper_outer.end() - 1);
  for (int b = 0; b < n; ++b) {
    for (int e = lower_outer[b]; e < lower_outer[b + 1]; ++e) {
      const int pa = position[lower_inner[e]], pb = position[b];
      placed[fill[std::max(pa, pb)]++] = {std::min(pa, pb), e};
    }
  }
  for (int c = 0; c < n; ++c) std::sort(placed.begin() + upper_outer[c], placed.begin() + upper_outer[c + 1]);
  for (int i = 0; i < entries; ++i) {
    upper_inner[i] = placed[i].first;
    slot[placed[i].second] = i;
  }
  const std::vector<double> zeros(entries, 0.0);
  pattern = Eigen::Map<const SpMat>(n, n, entries, upper_outer.data(), upper_inner.data(), zeros.data());
  base = Eigen::VectorXd::Zero(entries);
  for (const auto& [e, value] : q_entries) base(slot[e]) += value;
  for (int& d : diagonal) d = slot[d];
  for (Term& t : terms) t.index = slot[t.index];
}

bool KktSolver::Factor(const Eigen::VectorXd& row_weight, const Eigen::VectorXd& bound_weight) {
  assembly_.Assemble(row_weight, bound_weight, &K_);
  if (!analysed_) {
    ldlt_.Analyse(K_);
    analysed_ = true;
  }
  // Near convergence sigma spans many orders of magnitude; a small diagonal shift,
  // grown on failure, keeps the factorisation defined.
  // The shift is added to K's own diagonal and taken off again after the factorisation
  // (no copy of K per iteration).
  Eigen::Map<Eigen::VectorXd> values(K_.valuePtr(), K_.nonZeros());
  double diag_max = 0.0;
  for (int index : assembly_.diagonal) diag_max = std::max(diag_max, std::abs(values(index)));
  bool factored = false;
  for (double shift = 1e-14; shift <= 1e-6 && !factored; shift *= 100.0) {
    const double added = shift * (1.0 + diag_max);
    for (int index : assembly_.diagonal) values(index) += added;
    factored = ldlt_.Factorize(K_);
    for (int index : assembly_.diagonal) values(index) -= added;
  }
  return factored;
}

Eigen::VectorXd KktSolver::Solve(const Eigen::VectorXd& rhs_x, double tolerance, int refinement_steps) const {
  const Eigen::VectorXd rhs = assembly_.Permute(rhs_x);
  Eigen::VectorXd dx_permuted = ldlt_.Solve(rhs);
  // Iterative refinement against the unshifted matrix: sigma's range (up to 1e15 near
  // convergence) costs the factorisation digits that this wins back. Early iterations
  // are accurate already, so a step is taken only while it is needed.
  const double rhs_norm = rhs.lpNorm<Eigen::Infinity>();
  for (int k = 0; k < refinement_steps; ++k) {
    const Eigen::VectorXd residual = rhs - K_.selfadjointView<Eigen::Upper>() * dx_permuted;
    if (residual.lpNorm<Eigen::Infinity>() <= kRefinementPerTolerance * tolerance * rhs_norm) break;
    dx_permuted += ldlt_.Solve(residual);
  }
  return assembly_.Unpermute(dx_permuted);
}

}  // namespace mfp
