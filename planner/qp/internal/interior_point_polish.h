#pragma once
// Crossover for the interior point (interior_point_qp.h): from an iterate near the
// optimum, guess which rows and bounds are active, solve the equality-constrained KKT
// system of that guess for x and the rows' multipliers, and check the answer in the
// problem's own data. A right guess gives the relaxation's optimum to rounding, and a
// floor equal to its objective; a wrong one is reported as not accepted (the interior
// point goes on). Private to planner/qp.
#include <Eigen/Core>

#include "planner/miqp/miqp.h"
#include "planner/qp/interior_point_qp.h"
#include "planner/qp/internal/interior_point_kkt.h"

namespace mfp {

struct ActiveSetPolish {
  bool accepted = false;
  Eigen::VectorXd x;         // in the box; the active bounds' variables exactly on them
  Eigen::VectorXd z_rows;    // the elastic rows' multipliers, >= 0 (InequalityForm order)
  Eigen::VectorXd gradient;  // g = Qx + c + G'z_rows
  double objective = 0.0;    // 0.5 x'Qx + c'x + constant
  // The box certificate of (x, z_rows), valid for any x and z_rows >= 0: every point of
  // the box that meets the rows costs at least
  //   f(x) + z_rows'(Gx - d) + sum_j min(g_j (lower_j - x_j), g_j (upper_j - x_j)).
  // -infinity when the KKT system could not be solved (no certificate).
  double floor = -kInfinity;
};

// Polishes the interior point's iterate (w, s, z) of f (built from p under lower/upper):
// a constraint is guessed active when its dual exceeds its slack; a row with both sides
// guessed active (an equality) gets one multiplier of either sign.
ActiveSetPolish PolishActiveSet(const InequalityForm& f, const Miqp& p, const Eigen::VectorXd& lower,
                                const Eigen::VectorXd& upper, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                                const Eigen::VectorXd& z, const ActiveSetPolishOptions& options);

}  // namespace mfp
