#pragma once
// The linear algebra of the interior-point QP solver (interior_point_qp.h): the elastic
// inequality form of a QP and its Newton matrix K = Q + G' diag(row_weight) G +
// diag(bound_weight), assembled into a fixed pattern and factorised by a sparse LDL'.
// Private to planner/qp.
#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/internal/sparse_ldlt.h"

namespace mfp {

using SpMat = Eigen::SparseMatrix<double>;

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

// p under the box lower/upper in that form, each row side's elastic variable costing
// penalty per unit (lower < upper, all finite).
InequalityForm BuildInequalityForm(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                   double penalty);

// The box certificate of a point x of the box [lower, upper] (the rows dualised, the box
// kept): for row multipliers z_rows >= 0 of the E elastic rows, their residuals
// rows_residual = Gx - d (first E entries of d) and g_j = gradient(j) of Qx + c + G'z_rows,
// every point y of the box that meets the rows costs at least
//   objective + z_rows'rows_residual + sum_j min(g_j (lower_j - x_j), g_j (upper_j - x_j))
// (convexity), objective being f(x) with its constant. The interior point's BoxFloor and
// the crossover's polished point both certify with it.
template <class Gradient>
double BoxCertificate(double objective, const Eigen::Ref<const Eigen::VectorXd>& z_rows,
                      const Eigen::VectorXd& rows_residual, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                      const Eigen::Ref<const Eigen::VectorXd>& x, const Gradient& gradient) {
  double floor = objective + z_rows.dot(rows_residual);
  for (int j = 0; j < lower.size(); ++j) {
    const double gj = gradient(j);
    floor += gj > 0.0 ? gj * (lower(j) - x(j)) : gj * (upper(j) - x(j));
  }
  return floor;
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

  // The deadline passed while the pattern was built (checked every few hundred
  // columns): the assembly is incomplete and must not be used.
  bool interrupted = false;

  // The pattern is built column by column from G's rows, as a symbolic product with a
  // marker array, not from sparse products and conversions: per QP those took more
  // than one interior-point iteration.
  KktAssembly(const InequalityForm& f, const Deadline& deadline);

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

// Terms of the symbolic product G'G the assembly stores (one per pair of variables
// sharing a row, 16 bytes each): its work and memory, known before it is built.
double KktProductTerms(const InequalityForm& f);

// K factorised once per iteration: its pattern is fixed through a solve (analysed once:
// SparseLdlt records the factors' patterns then), its values scattered in place.
class KktSolver {
 public:
  KktSolver(const InequalityForm& f, const Deadline& deadline) : assembly_(f, deadline), K_(assembly_.pattern) {}

  // False when the deadline interrupted the assembly: Factor must not be called.
  bool ready() const { return !assembly_.interrupted; }

  // Factorises K for these weights; false when it cannot be, even shifted.
  bool Factor(const Eigen::VectorXd& row_weight, const Eigen::VectorXd& bound_weight);
  // K^-1 rhs_x, both in the original variable order, refined against the unshifted K while its residual is
  // above a hundredth of tolerance, relative to the right-hand side (refinement_steps at most).
  Eigen::VectorXd Solve(const Eigen::VectorXd& rhs_x, double tolerance, int refinement_steps) const;

 private:
  const KktAssembly assembly_;
  SpMat K_;
  SparseLdlt ldlt_;
  bool analysed_ = false;
};

}  // namespace mfp
