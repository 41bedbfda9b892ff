#include "planner/qp/internal/interior_point_polish.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <vector>

namespace mfp {
namespace {

// A row whose sides are this close (relative to 1 + |upper|) is an equality: with both
// sides guessed active it gets one multiplier of either sign.
constexpr double kEqualityWidth = 1e-12;

// The guess, and the KKT unknowns' starting values: the free variables' x and the
// active rows' multipliers.
struct ActiveSetGuess {
  std::vector<int> free;      // variables not on a bound
  std::vector<int> position;  // per variable: its index in free, or -1 (on a bound)
  Eigen::VectorXd x;          // w's x with the active bounds' variables on them
  std::vector<int> rows;      // active elastic rows k (G's row k, d_k its bound)
  std::vector<int> partner;   // per active row: an equality's other side, or -1
  Eigen::VectorXd multiplier;
};

bool GuessedActive(const Eigen::VectorXd& s, const Eigen::VectorXd& z, int k) { return z(k) > s(k); }

// Of two sides both guessed active, the one with the larger dual-to-slack ratio.
bool FirstSideWins(const Eigen::VectorXd& s, const Eigen::VectorXd& z, int first, int second) {
  return z(first) * s(second) >= z(second) * s(first);
}

void GuessBounds(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                 const Eigen::VectorXd& s, const Eigen::VectorXd& z, ActiveSetGuess* g) {
  const int n = f.n, E = f.elastic;
  g->position.assign(n, -1);
  for (int j = 0; j < n; ++j) {
    const int ku = 2 * E + 2 * j, kl = ku + 1;
    const bool up = GuessedActive(s, z, ku), lo = GuessedActive(s, z, kl);
    if (up && (!lo || FirstSideWins(s, z, ku, kl))) {
      g->x(j) = upper(j);
    } else if (lo) {
      g->x(j) = lower(j);
    } else {
      g->position[j] = static_cast<int>(g->free.size());
      g->free.push_back(j);
    }
  }
}

// The elastic rows in BuildInequalityForm's order: for each row of p, its upper
// side (if finite), then its lower side (if finite).
void GuessRows(const Miqp& p, const Eigen::VectorXd& s, const Eigen::VectorXd& z, ActiveSetGuess* g) {
  std::vector<double> multiplier;
  int k = 0;
  for (int i = 0; i < p.num_rows(); ++i) {
    const int ku = std::isfinite(p.row_upper(i)) ? k++ : -1;
    const int kl = std::isfinite(p.row_lower(i)) ? k++ : -1;
    const bool up = ku >= 0 && GuessedActive(s, z, ku), lo = kl >= 0 && GuessedActive(s, z, kl);
    if (up && lo && p.row_upper(i) - p.row_lower(i) <= kEqualityWidth * (1.0 + std::abs(p.row_upper(i)))) {
      g->rows.push_back(ku);
      g->partner.push_back(kl);
      multiplier.push_back(z(ku) - z(kl));
    } else if (up && (!lo || FirstSideWins(s, z, ku, kl))) {
      g->rows.push_back(ku);
      g->partner.push_back(-1);
      multiplier.push_back(z(ku));
    } else if (lo) {
      g->rows.push_back(kl);
      g->partner.push_back(-1);
      multiplier.push_back(z(kl));
    }
  }
  g->multiplier = Eigen::Map<const Eigen::VectorXd>(multiplier.data(), static_cast<Eigen::Index>(multiplier.size()));
}

// The upper triangle of [Q_FF + dI, G_AF'; G_AF, -dI] (F: free variables, A: active rows).
SpMat KktMatrix(const InequalityForm& f, const ActiveSetGuess& g, double regularisation) {
  const int nf = static_cast<int>(g.free.size()), na = static_cast<int>(g.rows.size());
  std::vector<Eigen::Triplet<double>> t;
  for (int jf = 0; jf < nf; ++jf) {
    for (SpMat::InnerIterator it(f.Q, g.free[jf]); it; ++it) {
      const int i = g.position[it.row()];
      if (i >= 0 && i <= jf) t.emplace_back(i, jf, it.value());
    }
    t.emplace_back(jf, jf, regularisation);
  }
  for (int a = 0; a < na; ++a) {
    for (SpMat::InnerIterator it(f.Gt, g.rows[a]); it; ++it) {
      const int j = g.position[it.row()];
      if (j >= 0) t.emplace_back(j, nf + a, it.value());
    }
    t.emplace_back(nf + a, nf + a, -regularisation);
  }
  SpMat K(nf + na, nf + na);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

// The elastic rows' multipliers of the guess (an equality's on the side of its sign);
// one-sided rows' may be negative until clipped.
Eigen::VectorXd RowMultipliers(const InequalityForm& f, const ActiveSetGuess& g) {
  Eigen::VectorXd z_rows = Eigen::VectorXd::Zero(f.elastic);
  for (size_t a = 0; a < g.rows.size(); ++a) {
    const double u = g.multiplier(static_cast<Eigen::Index>(a));
    if (g.partner[a] >= 0 && u < 0.0) {
      z_rows(g.partner[a]) = -u;
    } else {
      z_rows(g.rows[a]) = u;
    }
  }
  return z_rows;
}

// The unregularised KKT system's residual at the guess's x and multipliers.
Eigen::VectorXd KktResidual(const InequalityForm& f, const ActiveSetGuess& g) {
  const int nf = static_cast<int>(g.free.size()), na = static_cast<int>(g.rows.size());
  const Eigen::VectorXd gradient = f.Q * g.x + f.q.head(f.n) + f.Gt * RowMultipliers(f, g);
  const Eigen::VectorXd gx = f.G * g.x;
  Eigen::VectorXd r(nf + na);
  for (int jf = 0; jf < nf; ++jf) r(jf) = -gradient(g.free[jf]);
  for (int a = 0; a < na; ++a) r(nf + a) = f.d(g.rows[a]) - gx(g.rows[a]);
  return r;
}

// Solves the guess's KKT system from its starting values: one regularised solve, then
// refinement steps against the unregularised residual.
bool SolveKkt(const InequalityForm& f, const ActiveSetPolishOptions& options, ActiveSetGuess* g) {
  const int nf = static_cast<int>(g->free.size());
  if (nf + g->multiplier.size() == 0) return true;
  const Eigen::SimplicialLDLT<SpMat, Eigen::Upper> ldlt(KktMatrix(f, *g, options.regularisation));
  if (ldlt.info() != Eigen::Success) return false;
  for (int step = 0; step <= options.refinement_steps; ++step) {
    const Eigen::VectorXd delta = ldlt.solve(KktResidual(f, *g));
    if (!delta.allFinite()) return false;
    for (int jf = 0; jf < nf; ++jf) g->x(g->free[jf]) += delta(jf);
    g->multiplier += delta.tail(g->multiplier.size());
  }
  return true;
}

}  // namespace

ActiveSetPolish PolishActiveSet(const InequalityForm& f, const Miqp& p, const Eigen::VectorXd& lower,
                                const Eigen::VectorXd& upper, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                                const Eigen::VectorXd& z, const ActiveSetPolishOptions& options) {
  const int n = f.n, E = f.elastic;
  ActiveSetPolish polish;
  ActiveSetGuess g;
  g.x = w.head(n);
  GuessBounds(f, lower, upper, s, z, &g);
  GuessRows(p, s, z, &g);
  if (!SolveKkt(f, options, &g)) return polish;

  const double tolerance = options.primal_tolerance * (1.0 + f.d.lpNorm<Eigen::Infinity>());
  double violation = 0.0;
  for (int j : g.free) violation = std::max({violation, lower(j) - g.x(j), g.x(j) - upper(j)});
  polish.x = g.x.cwiseMax(lower).cwiseMin(upper);
  const Eigen::VectorXd gx = f.G * polish.x;
  if (E > 0) violation = std::max(violation, (gx - f.d.head(E)).maxCoeff());

  polish.z_rows = RowMultipliers(f, g).cwiseMax(0.0);
  const Eigen::VectorXd qx = f.Q * polish.x;
  polish.gradient = qx + p.c + f.Gt * polish.z_rows;
  polish.objective = 0.5 * polish.x.dot(qx) + p.c.dot(polish.x) + p.constant;
  double floor = polish.objective + polish.z_rows.dot(gx - f.d.head(E));
  for (int j = 0; j < n; ++j) {
    const double gj = polish.gradient(j);
    floor += std::min(gj * (lower(j) - polish.x(j)), gj * (upper(j) - polish.x(j)));
  }
  polish.floor = std::min(floor, polish.objective);
  polish.accepted = std::isfinite(floor) && violation <= tolerance &&
                    polish.objective - floor <= options.gap * std::max(1.0, std::abs(polish.objective));
  return polish;
}

}  // namespace mfp
