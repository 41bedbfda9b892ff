#include "planner/qp/interior_point_qp.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <vector>

#include "planner/base/check.h"

namespace mfp {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// A Newton system solved to this relative residual, as a multiple of the solve's
// tolerance, needs no refinement step: 1e-10 at the search's 1e-8, 1e-8 at
// relax-and-fix's stage accuracy of 1e-6, where refining further took a third more
// triangular solves and changed no iterate count or plan (docs/measurements.md).
constexpr double kRefinementPerTolerance = 0.01;

// The problem as  min 0.5 w'Hw + q'w  s.t.  C w <= d,  w = (x, e).
// Rows of C, in this order: [0, E) the elastic rows a'x - e_k <= b, [E, 2E) e_k >= 0,
// then for each variable j its upper and lower bound (rows 2E + 2j and 2E + 2j + 1).
struct InequalityForm {
  int n = 0;        // original variables
  int elastic = 0;  // elastic variables (one per one-sided row), E above
  SpMat G;          // x part of the elastic rows (E x n)
  SpMat Gt;         // its transpose
  SpMat Q;          // x part of H
  Eigen::VectorXd q, d;

  // C w without forming C: the elastic rows, e >= 0, then each variable's bound pair.
  Eigen::VectorXd C(const Eigen::VectorXd& w) const {
    const int E = elastic;
    Eigen::VectorXd out(2 * E + 2 * n);
    out.head(E) = G * w.head(n) - w.tail(E);
    out.segment(E, E) = -w.tail(E);
    for (int j = 0; j < n; ++j) {
      out(2 * E + 2 * j) = w(j);
      out(2 * E + 2 * j + 1) = -w(j);
    }
    return out;
  }
  // C'v.
  Eigen::VectorXd Ct(const Eigen::VectorXd& v) const {
    const int E = elastic;
    Eigen::VectorXd out(n + E);
    out.head(n) = Gt * v.head(E);
    for (int j = 0; j < n; ++j) out(j) += v(2 * E + 2 * j) - v(2 * E + 2 * j + 1);
    out.tail(E) = -v.head(E) - v.segment(E, E);
    return out;
  }
};

InequalityForm Build(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
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

// An approximate minimum degree order of a symmetric pattern (lower triangle given).
std::vector<int> MinimumDegreeOrder(const SpMat& lower) {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(lower, amd);  // amd.indices()(k): the variable eliminated k-th
  return std::vector<int>(amd.indices().data(), amd.indices().data() + amd.indices().size());
}

// Fills K = Q + G' diag(row_weight) G + diag(bound_weight) into a fixed pattern, with
// the variables in elimination order: K's upper triangle is stored already permuted,
// so the factorisation neither orders nor copies it (NaturalOrdering reads an upper
// triangle in place).
struct KktAssembly {
  SpMat pattern;                  // upper triangle of P (Q + G'G + I) P'
  std::vector<int> position;      // variable j's row and column in the permuted K
  Eigen::VectorXd base;           // Q's values at their positions in the pattern
  std::vector<int> diagonal;      // value index of (j, j)
  struct Term {
    int row;       // row k of G
    int index;     // value index in the pattern
    double coef;   // G(k, a) G(k, b)
  };
  std::vector<Term> terms;

  // The pattern is built column by column from G's rows, as a symbolic product with a
  // marker array, not from sparse products and conversions: per QP those took more
  // than one interior-point iteration.
  explicit KktAssembly(const InequalityForm& f) {
    const int n = f.n;
    // 1. The lower triangle of Q + G'G + I in the original order (compressed columns,
    //    sorted rows). entry_of[a] is row a's entry in the column being built.
    std::vector<int> lower_outer(n + 1, 0), lower_inner;
    std::vector<int> mark(n, -1), entry_of(n, -1);
    std::vector<std::pair<int, double>> q_entries;  // (entry, value)
    diagonal.resize(n);
    for (int col = 0; col < n; ++col) {
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

  void Assemble(const Eigen::VectorXd& row_weight, const Eigen::VectorXd& bound_weight, SpMat* K) const {
    Eigen::Map<Eigen::VectorXd> values(K->valuePtr(), K->nonZeros());
    values = base;
    for (const Term& t : terms) values(t.index) += row_weight(t.row) * t.coef;
    for (size_t j = 0; j < diagonal.size(); ++j) values(diagonal[j]) += bound_weight(j);
  }
  // v in the permuted order, and back.
  Eigen::VectorXd Permute(const Eigen::VectorXd& v) const {
    Eigen::VectorXd out(v.size());
    for (size_t j = 0; j < position.size(); ++j) out(position[j]) = v(static_cast<Eigen::Index>(j));
    return out;
  }
  Eigen::VectorXd Unpermute(const Eigen::VectorXd& v) const {
    Eigen::VectorXd out(v.size());
    for (size_t j = 0; j < position.size(); ++j) out(static_cast<Eigen::Index>(j)) = v(position[j]);
    return out;
  }
};

// Largest alpha in (0, 1] keeping v + alpha dv >= 0 (v > 0), given inverse_v = 1 / v:
// alpha = 1 / max(1, max_i -dv_i / v_i). One multiplying pass, no division, as it runs
// four times per iteration over every row and bound.
double MaxStep(const Eigen::VectorXd& inverse_v, const Eigen::VectorXd& dv) {
  return 1.0 / std::max(1.0, (-dv).cwiseProduct(inverse_v).maxCoeff());
}

// The floor below of any iterate (z >= 0): no point of the box that meets the rows costs
// less. The derivation is SetCostRates's. objective: 0.5 x'Qx + c'x + constant at w.
double LagrangianFloor(const InequalityForm& f, double objective, const Eigen::VectorXd& lower,
                       const Eigen::VectorXd& upper, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                       const Eigen::VectorXd& z, const Eigen::VectorXd& r_d, const Eigen::VectorXd& r_p) {
  const int n = f.n, E = f.elastic;
  const double elastic_cost = f.q.tail(E).dot(w.tail(E));
  double residual = 0.0;
  for (int j = 0; j < n; ++j) {
    residual += std::abs(r_d(j)) * std::max(upper(j) - w(j), w(j) - lower(j));
  }
  for (int k = 0; k < E; ++k) residual += std::abs(r_d(n + k)) * std::abs(w(n + k));
  return objective + elastic_cost + z.dot(r_p - s) - residual;
}

// The reduced-cost certificate of RelaxationResult from the final iterate. With the
// Lagrangian L(w) = f_el(w) + z'(C w - d) (f_el: objective plus elastic penalty), any
// point x of the box that meets the rows (so e = 0) satisfies
//   f(x) >= L(w) + sum_j z_l,j (x_j - l_j) + z_u,j (u_j - x_j)
// (the row terms left out are >= 0), and by convexity L(w) >= L(w*) + r_d'(w - w*),
// where L(w*) = f_el(w*) + z'(r_p - s). The residual term is bounded over the box and
// the elastic part (w_e = 0 against w*_e), so the floor holds for the inexact iterate.
void SetCostRates(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                  const Eigen::VectorXd& w, const Eigen::VectorXd& s, const Eigen::VectorXd& z,
                  const Eigen::VectorXd& r_d, const Eigen::VectorXd& r_p, RelaxationResult* result) {
  const int n = f.n, E = f.elastic;
  result->cost_floor =
      std::min(result->objective, LagrangianFloor(f, result->objective, lower, upper, w, s, z, r_d, r_p));
  result->lower_cost_rate.resize(n);
  result->upper_cost_rate.resize(n);
  for (int j = 0; j < n; ++j) {
    result->upper_cost_rate(j) = std::max(0.0, z(2 * E + 2 * j));
    result->lower_cost_rate(j) = std::max(0.0, z(2 * E + 2 * j + 1));
  }
}

// Cold start: x in the middle of its box, e covering the rows' violations plus one,
// slacks of at least one, duals of one (half the penalty for the elastic pairs: their
// dual feasibility reads penalty = z(row) + z(e >= 0)).
void ColdStart(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
               const InteriorPointOptions& opt, Eigen::VectorXd* w, Eigen::VectorXd* s, Eigen::VectorXd* z) {
  const int n = f.n, E = f.elastic;
  *w = Eigen::VectorXd::Zero(n + E);
  for (int j = 0; j < n; ++j) (*w)(j) = 0.5 * (lower(j) + upper(j));
  const Eigen::VectorXd gx = f.G * w->head(n);
  for (int k = 0; k < E; ++k) (*w)(n + k) = std::max(0.0, gx(k) - f.d(k)) + 1.0;
  *s = (f.d - f.C(*w)).cwiseMax(1.0);
  *z = Eigen::VectorXd::Ones(f.d.size());
  z->head(2 * E).setConstant(0.5 * opt.elastic_penalty);
}

// Warm start from a point x0 (a parent node's solution): x near x0, and for every
// inequality a slack-dual pair with product mu0 = warm_start_complementarity. A row
// that x meets with slack r gets dual mu0 / r; its elastic variable takes what is left
// of the penalty as its dual and mu0 over that as its value (tiny). A row that x
// violates or nearly meets gets slack warm_start_min_slack, its elastic variable
// covering the rest. The cold start's products are of the order of the penalty, so the
// warm one starts many orders of magnitude closer to complementarity.
void WarmStart(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
               const Eigen::VectorXd& x0, const InteriorPointOptions& opt, Eigen::VectorXd* w, Eigen::VectorXd* s,
               Eigen::VectorXd* z) {
  const int n = f.n, E = f.elastic;
  const double mu0 = opt.warm_start_complementarity, min_slack = opt.warm_start_min_slack;
  const double penalty = opt.elastic_penalty;
  MFP_CHECK(mu0 > 0.0 && min_slack > 0.0 && opt.warm_start_pull > 0.0 && opt.warm_start_pull <= 1.0);
  *w = Eigen::VectorXd::Zero(n + E);
  *s = Eigen::VectorXd::Zero(f.d.size());
  *z = Eigen::VectorXd::Zero(f.d.size());
  for (int j = 0; j < n; ++j) {
    const double mid = 0.5 * (lower(j) + upper(j));
    (*w)(j) = (1.0 - opt.warm_start_pull) * std::clamp(x0(j), lower(j), upper(j)) + opt.warm_start_pull * mid;
    // Bound slacks strictly positive: on a box narrower than the rounding error of its
    // ends (bound propagation leaves such boxes) the pulled point can land on a bound,
    // and a zero slack made the duals infinite and the whole solve NaN (then Ipopt
    // solved it, 25 times slower). The slacks need not equal the distances exactly: the
    // primal residual carries the difference.
    const double floor = std::max(std::min(min_slack, 0.25 * (upper(j) - lower(j))),
                                  1e-9 * (1.0 + std::max(std::abs(lower(j)), std::abs(upper(j)))));
    (*s)(2 * E + 2 * j) = std::max(upper(j) - (*w)(j), floor);
    (*s)(2 * E + 2 * j + 1) = std::max((*w)(j) - lower(j), floor);
    (*z)(2 * E + 2 * j) = mu0 / (*s)(2 * E + 2 * j);
    (*z)(2 * E + 2 * j + 1) = mu0 / (*s)(2 * E + 2 * j + 1);
  }
  const Eigen::VectorXd gx = f.G * w->head(n);
  for (int k = 0; k < E; ++k) {
    const double slack = f.d(k) - gx(k);  // of the row without its elastic variable
    double e, z_row;
    if (slack >= min_slack) {
      z_row = std::min(mu0 / slack, 0.5 * penalty);
      e = mu0 / (penalty - z_row);
    } else {
      z_row = std::min(mu0 / min_slack, 0.5 * penalty);
      e = min_slack - slack;
    }
    (*w)(n + k) = e;
    (*s)(k) = slack + e;
    (*z)(k) = z_row;
    (*s)(E + k) = e;
    (*z)(E + k) = penalty - z_row;
  }
}

}  // namespace

RelaxationResult SolveQpInteriorPoint(const Miqp& p, const Eigen::VectorXd& lower,
                                      const Eigen::VectorXd& upper, const Eigen::VectorXd* warm_start,
                                      const InteriorPointOptions& opt) {
  const InequalityForm f = Build(p, lower, upper, opt.elastic_penalty);
  const int n = f.n;
  const int m = static_cast<int>(f.d.size());
  RelaxationResult result;

  Eigen::VectorXd w, s, z;
  if (warm_start != nullptr) {
    WarmStart(f, lower, upper, *warm_start, opt, &w, &s, &z);
  } else {
    ColdStart(f, lower, upper, opt, &w, &s, &z);
  }

  const double scale_d = 1.0 + f.d.lpNorm<Eigen::Infinity>();
  const double scale_c = 1.0 + p.c.lpNorm<Eigen::Infinity>();
  Eigen::SimplicialLDLT<SpMat, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt;
  bool analysed = false;
  // K = Q + G' diag(w) G + diag(b) keeps one sparsity pattern through the solve; its
  // values are scattered in place each iteration instead of forming sparse products.
  const KktAssembly assembly(f);
  SpMat K = assembly.pattern;
  const SpMat& Gt = f.Gt;

  for (int iter = 0; iter < opt.max_iterations; ++iter) {
    result.iterations = iter;
    if (opt.deadline.Expired()) break;  // kIterationLimit below
    // Q x once per iteration: the dual residual, the objective and the dual scale use it.
    const Eigen::VectorXd qx = f.Q * w.head(n);
    Eigen::VectorXd r_d = f.q;
    r_d.head(n) += qx;
    r_d += f.Ct(z);
    const Eigen::VectorXd r_p = f.C(w) + s - f.d;
    const double mu = s.dot(z) / m;
    const double dual_x = r_d.head(n).lpNorm<Eigen::Infinity>();
    const double dual_e = f.elastic ? r_d.tail(f.elastic).lpNorm<Eigen::Infinity>() : 0.0;
    const double objective = 0.5 * w.head(n).dot(qx) + p.c.dot(w.head(n));
    // Converged: primal feasible and complementary to the tolerance, and dual feasible
    // to the tolerance or, once complementarity is far below it, to an acceptable level.
    // (Normal equations lose digits in the duals of active bounds as sigma grows; the
    // objective has settled long before, which is what a bound needs.)
    const double scale_x = scale_c + qx.lpNorm<Eigen::Infinity>();
    const bool primal_ok = r_p.lpNorm<Eigen::Infinity>() <= opt.tolerance * scale_d;
    const bool complementary = mu <= opt.tolerance * (1.0 + std::abs(objective));
    const bool dual_ok = dual_x <= opt.tolerance * scale_x && dual_e <= opt.tolerance * opt.elastic_penalty;
    const bool dual_acceptable = complementary &&
                                 dual_x <= opt.acceptable_dual * scale_x &&
                                 dual_e <= opt.acceptable_dual * opt.elastic_penalty;
    if (primal_ok && complementary && (dual_ok || dual_acceptable)) {
      result.x = w.head(n);
      result.objective = objective + p.constant;
      const double violation = f.elastic ? w.tail(f.elastic).maxCoeff() : 0.0;
      const double threshold =
          std::max(opt.infeasible_violation, opt.infeasible_violation_per_tolerance * opt.tolerance * scale_d);
      result.status = violation > threshold ? RelaxationStatus::kInfeasible : RelaxationStatus::kSolved;
      if (result.status == RelaxationStatus::kSolved) {
        SetCostRates(f, lower, upper, w, s, z, r_d, r_p, &result);
      }
      return result;
    }
    // A node that cannot beat the incumbent is settled as soon as the floor proves it,
    // often many iterations before convergence.
    if (opt.cutoff < kInfinity) {
      const double floor = LagrangianFloor(f, objective + p.constant, lower, upper, w, s, z, r_d, r_p);
      if (floor >= opt.cutoff) {
        result.status = RelaxationStatus::kCutoff;
        result.x = w.head(n);
        result.objective = floor;
        return result;
      }
    }
    const Eigen::VectorXd inverse_s = s.cwiseInverse();
    const Eigen::VectorXd inverse_z = z.cwiseInverse();
    const Eigen::VectorXd sigma = z.cwiseProduct(inverse_s);
    // The Newton system (H + C'SC) dw = t has a diagonal block for the elastic variables
    // (each appears in its own row and in e >= 0 only), so it is eliminated: with S1, S2
    // the weights of those two rows and Sb the bound rows' weights,
    //   K dx = t_x + G' (S1 / (S1 + S2) t_e),  K = Q + G' diag(S1 S2 / (S1 + S2)) G + Sb,
    //   de = (t_e + S1 G dx) / (S1 + S2).
    // K has the size of x alone.
    const int E = f.elastic;
    const Eigen::VectorXd s1 = sigma.head(E), s2 = sigma.segment(E, E);
    const Eigen::VectorXd s12 = s1 + s2;
    const Eigen::VectorXd row_weight = s1.cwiseProduct(s2).cwiseQuotient(s12);
    Eigen::VectorXd bound_weight(n);
    for (int j = 0; j < n; ++j) bound_weight(j) = sigma(2 * E + 2 * j) + sigma(2 * E + 2 * j + 1);
    assembly.Assemble(row_weight, bound_weight, &K);
    if (!analysed) {
      ldlt.analyzePattern(K);
      analysed = true;
    }
    // Near convergence sigma spans many orders of magnitude; a small diagonal shift,
    // grown on failure, keeps the factorisation defined.
    // The shift is added to K's own diagonal and taken off again after the factorisation
    // (no copy of K per iteration).
    Eigen::Map<Eigen::VectorXd> values(K.valuePtr(), K.nonZeros());
    double diag_max = 0.0;
    for (int index : assembly.diagonal) diag_max = std::max(diag_max, std::abs(values(index)));
    bool factored = false;
    for (double shift = 1e-14; shift <= 1e-6 && !factored; shift *= 100.0) {
      const double added = shift * (1.0 + diag_max);
      for (int index : assembly.diagonal) values(index) += added;
      ldlt.factorize(K);
      factored = ldlt.info() == Eigen::Success;
      for (int index : assembly.diagonal) values(index) -= added;
    }
    if (!factored) break;
    // Newton direction for a complementarity target rc:
    //   (H + C'SC) dw = -r_d - C'(S r_p + S^-1 rc),  ds = -r_p - C dw,  dz = S(C dw + r_p) + S^-1 rc.
    // With v = S r_p + S^-1 rc split by row groups (v_R the elastic rows, v_P their
    // e >= 0 rows, v_U and v_L the bound pairs), t = -r_d - C'v reads
    //   t_x = -r_d,x - G'v_R - (v_U - v_L),  t_e = -r_d,e + v_R + v_P,
    // so the right-hand side K dx = t_x + G'(S1 t_e / (S1 + S2)) needs one product with
    // G' and C dw one with G (G dx, which de needs too).
    auto direction = [&](const Eigen::VectorXd& rc, Eigen::VectorXd* dw, Eigen::VectorXd* ds, Eigen::VectorXd* dz) {
      const Eigen::VectorXd v = sigma.cwiseProduct(r_p) + rc.cwiseProduct(inverse_s);
      const Eigen::VectorXd t_e = -r_d.tail(E) + v.head(E) + v.segment(E, E);
      const Eigen::VectorXd row_part = s1.cwiseProduct(t_e).cwiseQuotient(s12) - v.head(E);
      Eigen::VectorXd rhs_x = Gt * row_part - r_d.head(n);
      for (int j = 0; j < n; ++j) rhs_x(j) -= v(2 * E + 2 * j) - v(2 * E + 2 * j + 1);
      const Eigen::VectorXd rhs = assembly.Permute(rhs_x);
      Eigen::VectorXd dx_permuted = ldlt.solve(rhs);
      // Iterative refinement against the unshifted matrix: sigma's range (up to 1e15
      // near convergence) costs the factorisation digits that this wins back. Early
      // iterations are accurate already, so a step is taken only while it is needed.
      const double rhs_norm = rhs.lpNorm<Eigen::Infinity>();
      for (int k = 0; k < 2; ++k) {
        const Eigen::VectorXd residual = rhs - K.selfadjointView<Eigen::Upper>() * dx_permuted;
        if (residual.lpNorm<Eigen::Infinity>() <= kRefinementPerTolerance * opt.tolerance * rhs_norm) break;
        dx_permuted += ldlt.solve(residual);
      }
      const Eigen::VectorXd dx = assembly.Unpermute(dx_permuted);
      const Eigen::VectorXd g_dx = f.G * dx;
      dw->resize(n + E);
      dw->head(n) = dx;
      dw->tail(E) = (t_e + s1.cwiseProduct(g_dx)).cwiseQuotient(s12);
      Eigen::VectorXd c_dw(m);  // C dw from G dx
      c_dw.head(E) = g_dx - dw->tail(E);
      c_dw.segment(E, E) = -dw->tail(E);
      for (int j = 0; j < n; ++j) {
        c_dw(2 * E + 2 * j) = dx(j);
        c_dw(2 * E + 2 * j + 1) = -dx(j);
      }
      *ds = -r_p - c_dw;
      *dz = sigma.cwiseProduct(c_dw + r_p) + rc.cwiseProduct(inverse_s);
    };
    Eigen::VectorXd dw, ds, dz;
    direction(-s.cwiseProduct(z), &dw, &ds, &dz);  // predictor (affine scaling)
    const double alpha_aff = std::min(MaxStep(inverse_s, ds), MaxStep(inverse_z, dz));
    const double mu_aff = (s + alpha_aff * ds).dot(z + alpha_aff * dz) / m;
    const double centering = std::pow(mu_aff / mu, 3);
    const Eigen::VectorXd rc = -s.cwiseProduct(z) - ds.cwiseProduct(dz) + Eigen::VectorXd::Constant(m, centering * mu);
    direction(rc, &dw, &ds, &dz);  // corrector
    const double alpha = std::min(1.0, 0.99 * std::min(MaxStep(inverse_s, ds), MaxStep(inverse_z, dz)));
    w += alpha * dw;
    s += alpha * ds;
    z += alpha * dz;
  }
  result.status = RelaxationStatus::kIterationLimit;
  result.x = w.head(n);
  result.objective = p.Objective(result.x);
  return result;
}

}  // namespace mfp
