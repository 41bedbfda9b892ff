#include "planner/qp/internal/interior_point_polish.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace mfp {
namespace {

// A row whose sides are this close (relative to 1 + |upper|) is an equality: with both
// sides guessed active it gets one multiplier of either sign.
constexpr double kEqualityWidth = 1e-12;

// Which side of each variable's box and of each row of p is guessed active, and each
// row's elastic rows (BuildInequalityForm's order: its upper side, then its lower side,
// each where finite; -1 where not).
struct ActiveSet {
  std::vector<signed char> var;  // 0: free, 1: on its upper bound, -1: on its lower bound
  std::vector<signed char> row;  // 0: inactive, 1: upper side, -1: lower side, 2: both (an equality)
  std::vector<int> upper_side, lower_side;
};

// The KKT system of an active set: its unknowns (the free variables' x, the active rows'
// multipliers) with their starting values.
struct ActiveSetGuess {
  std::vector<int> free;      // variables not on a bound
  std::vector<int> position;  // per variable: its index in free, or -1 (on a bound)
  Eigen::VectorXd x;          // the active bounds' variables on them
  std::vector<int> rows;      // active elastic rows k (G's row k, d_k its bound)
  std::vector<int> partner;   // per active row: an equality's other side, or -1
  Eigen::VectorXd multiplier;
};

// A side is guessed active when its dual exceeds its slack or its slack is below
// slack_floor (sqrt of the mean complementarity: a degenerate constraint's slack and dual
// both fall like it, and leaving such a constraint out makes the KKT system singular on
// variables without cost; a constraint guessed active in error comes out of the set with a
// negative multiplier).
bool GuessedActive(const Eigen::VectorXd& s, const Eigen::VectorXd& z, int k, double slack_floor) {
  return k >= 0 && (z(k) > s(k) || s(k) < slack_floor);
}

// Of two sides both guessed active, the one with the larger dual-to-slack ratio.
bool FirstSideWins(const Eigen::VectorXd& s, const Eigen::VectorXd& z, int first, int second) {
  return z(first) * s(second) >= z(second) * s(first);
}

// A side of a constraint is guessed active when its dual exceeds its slack.
ActiveSet InitialSet(const InequalityForm& f, const Miqp& p, const Eigen::VectorXd& s, const Eigen::VectorXd& z) {
  const int n = f.n, E = f.elastic;
  const double slack_floor = std::sqrt(s.dot(z) / static_cast<double>(s.size()));
  ActiveSet set;
  set.var.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    const int ku = 2 * E + 2 * j, kl = ku + 1;
    const bool up = GuessedActive(s, z, ku, slack_floor), lo = GuessedActive(s, z, kl, slack_floor);
    set.var[j] = up && (!lo || FirstSideWins(s, z, ku, kl)) ? 1 : (lo ? -1 : 0);
  }
  int k = 0;
  for (int i = 0; i < p.num_rows(); ++i) {
    const int ku = std::isfinite(p.row_upper(i)) ? k++ : -1;
    const int kl = std::isfinite(p.row_lower(i)) ? k++ : -1;
    set.upper_side.push_back(ku);
    set.lower_side.push_back(kl);
    const bool up = GuessedActive(s, z, ku, slack_floor), lo = GuessedActive(s, z, kl, slack_floor);
    if (up && lo && p.row_upper(i) - p.row_lower(i) <= kEqualityWidth * (1.0 + std::abs(p.row_upper(i)))) {
      set.row.push_back(2);
    } else {
      set.row.push_back(up && (!lo || FirstSideWins(s, z, ku, kl)) ? 1 : (lo ? -1 : 0));
    }
  }
  return set;
}

// The unknowns of set, started from x_start (the active bounds' variables moved onto
// them) and the elastic rows' multipliers z_rows.
ActiveSetGuess GuessFor(const ActiveSet& set, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                        const Eigen::VectorXd& x_start, const Eigen::VectorXd& z_rows) {
  ActiveSetGuess g;
  g.x = x_start;
  g.position.assign(set.var.size(), -1);
  for (size_t j = 0; j < set.var.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    if (set.var[j] == 1) {
      g.x(jj) = upper(jj);
    } else if (set.var[j] == -1) {
      g.x(jj) = lower(jj);
    } else {
      g.position[j] = static_cast<int>(g.free.size());
      g.free.push_back(static_cast<int>(j));
    }
  }
  std::vector<double> multiplier;
  for (size_t i = 0; i < set.row.size(); ++i) {
    const int ku = set.upper_side[i], kl = set.lower_side[i];
    if (set.row[i] == 0) continue;
    const int k = set.row[i] == -1 ? kl : ku;
    g.rows.push_back(k);
    g.partner.push_back(set.row[i] == 2 ? kl : -1);
    multiplier.push_back(set.row[i] == 2 ? z_rows(ku) - z_rows(kl) : z_rows(k));
  }
  g.multiplier = Eigen::Map<const Eigen::VectorXd>(multiplier.data(), static_cast<Eigen::Index>(multiplier.size()));
  return g;
}

// The upper triangle of [Q_FF + dI, G_AF'; G_AF, -dI] (F: free variables, A: active rows).
SpMat KktMatrix(const InequalityForm& f, const ActiveSetGuess& g, double regularisation) {
  const int nf = static_cast<int>(g.free.size()), na = static_cast<int>(g.rows.size());
  std::vector<Eigen::Triplet<double>> t;
  for (int jf = 0; jf < nf; ++jf) {
    double diagonal = 0.0;
    for (SpMat::InnerIterator it(f.Q, g.free[jf]); it; ++it) {
      const int i = g.position[it.row()];
      if (i >= 0 && i <= jf) t.emplace_back(i, jf, it.value());
      if (it.row() == g.free[jf]) diagonal = std::abs(it.value());
    }
    // Relative to Q's diagonal, so that a singular block of large costs keeps it in
    // rounding (an absolute shift below their last digit can leave exact zero pivots).
    t.emplace_back(jf, jf, regularisation * (1.0 + diagonal));
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
  Eigen::VectorXd residual = KktResidual(f, *g);
  for (int step = 0; step <= options.refinement_steps; ++step) {
    const Eigen::VectorXd delta = ldlt.solve(residual);
    if (!delta.allFinite()) return false;
    ActiveSetGuess next = *g;
    for (int jf = 0; jf < nf; ++jf) next.x(next.free[jf]) += delta(jf);
    next.multiplier += delta.tail(next.multiplier.size());
    Eigen::VectorXd next_residual = KktResidual(f, next);
    // A refinement step that does not shrink the residual by a tenth is not converging (the
    // system is singular and the right-hand side outside its range: a wrong guess):
    // the step is not taken.
    if (step > 0 && next_residual.lpNorm<Eigen::Infinity>() > 0.9 * residual.lpNorm<Eigen::Infinity>()) break;
    *g = std::move(next);
    residual = std::move(next_residual);
  }
  return true;
}

// Constraints that the solved guess g violates join the set: a free variable out of its
// box goes onto the bound it crossed, an inactive row becomes active on the side it
// crosses. Returns how many joined.
int AddViolated(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                const ActiveSetGuess& g, double primal_tolerance, ActiveSet* set) {
  int changes = 0;
  for (int j = 0; j < f.n; ++j) {
    if (set->var[j] != 0) continue;
    const signed char next = g.x(j) > upper(j) + primal_tolerance ? 1 : (g.x(j) < lower(j) - primal_tolerance ? -1 : 0);
    changes += next != 0;
    set->var[j] = next;
  }
  const Eigen::VectorXd gx = f.G * g.x;
  const auto violated = [&](int k) { return k >= 0 && gx(k) - f.d(k) > primal_tolerance; };
  for (size_t i = 0; i < set->row.size(); ++i) {
    if (set->row[i] != 0) continue;
    const signed char next = violated(set->upper_side[i]) ? 1 : (violated(set->lower_side[i]) ? -1 : 0);
    changes += next != 0;
    set->row[i] = next;
  }
  return changes;
}

// Constraints of the set whose multipliers at g have the wrong sign leave it (a bound's
// multiplier is the gradient's part on its variable; equalities stay). Returns how many left.
int DropWrongSigned(const InequalityForm& f, const ActiveSetGuess& g, double dual_tolerance, ActiveSet* set) {
  const Eigen::VectorXd z_rows = RowMultipliers(f, g);
  const Eigen::VectorXd gradient = f.Q * g.x + f.q.head(f.n) + f.Gt * z_rows;
  int changes = 0;
  for (int j = 0; j < f.n; ++j) {
    if ((set->var[j] == 1 && gradient(j) > dual_tolerance) || (set->var[j] == -1 && gradient(j) < -dual_tolerance)) {
      set->var[j] = 0;
      ++changes;
    }
  }
  for (size_t i = 0; i < set->row.size(); ++i) {
    const signed char side = set->row[i];
    if ((side == 1 && z_rows(set->upper_side[i]) < -dual_tolerance) ||
        (side == -1 && z_rows(set->lower_side[i]) < -dual_tolerance)) {
      set->row[i] = 0;
      ++changes;
    }
  }
  return changes;
}

// One primal-dual active-set correction of set from its solved guess g: the
// wrong-signed constraints leave it and the violated ones join it, both at once (the
// order chosen in docs/measurements.md). Returns the number of changes (0: g is primal
// and dual feasible to the tolerances).
int CorrectSet(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
               const ActiveSetGuess& g, double primal_tolerance, double dual_tolerance, ActiveSet* set) {
  const int dropped = DropWrongSigned(f, g, dual_tolerance, set);
  return dropped + AddViolated(f, lower, upper, g, primal_tolerance, set);
}

}  // namespace

ActiveSetPolish PolishActiveSet(const InequalityForm& f, const Miqp& p, const Eigen::VectorXd& lower,
                                const Eigen::VectorXd& upper, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                                const Eigen::VectorXd& z, const ActiveSetPolishOptions& options) {
  const int n = f.n, E = f.elastic;
  ActiveSetPolish polish;
  const double tolerance = options.primal_tolerance * (1.0 + f.d.lpNorm<Eigen::Infinity>());
  const double dual_tolerance = options.dual_tolerance * (1.0 + p.c.lpNorm<Eigen::Infinity>());
  ActiveSet set = InitialSet(f, p, s, z);
  Eigen::VectorXd z_start = z.head(E);
  ActiveSetGuess g;
  for (int round = 1;; ++round) {
    g = GuessFor(set, lower, upper, w.head(n), z_start);
    if (!SolveKkt(f, options, &g)) return polish;
    if (round >= options.max_rounds || CorrectSet(f, lower, upper, g, tolerance, dual_tolerance, &set) == 0) break;
    z_start = RowMultipliers(f, g);
  }

  double violation = 0.0;
  for (int j : g.free) violation = std::max({violation, lower(j) - g.x(j), g.x(j) - upper(j)});
  polish.x = g.x.cwiseMax(lower).cwiseMin(upper);
  const Eigen::VectorXd gx = f.G * polish.x;
  if (E > 0) violation = std::max(violation, (gx - f.d.head(E)).maxCoeff());

  polish.z_rows = RowMultipliers(f, g).cwiseMax(0.0);
  const Eigen::VectorXd qx = f.Q * polish.x;
  polish.gradient = qx + p.c + f.Gt * polish.z_rows;
  polish.objective = 0.5 * polish.x.dot(qx) + p.c.dot(polish.x) + p.constant;
  const double floor = BoxCertificate(polish.objective, polish.z_rows, gx - f.d.head(E), lower, upper, polish.x,
                                      [&polish](int j) { return polish.gradient(j); });
  polish.floor = std::isfinite(floor) ? std::min(floor, polish.objective) : -kInfinity;
  polish.accepted = std::isfinite(floor) && violation <= tolerance &&
                    polish.objective - floor <= options.gap * std::max(1.0, std::abs(polish.objective));
  return polish;
}

}  // namespace mfp
