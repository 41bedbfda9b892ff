// The interior point's crossover (interior_point_polish.h) on QPs solved by hand.
#include "planner/qp/internal/interior_point_polish.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "planner/miqp/miqp_builder.h"
#include "planner/qp/interior_point_qp.h"
#include "planner/qp/internal/interior_point_kkt.h"
#include "tests/test_qps.h"

namespace mfp {
namespace {

// min (x - 2)^2 + (y - 2)^2  s.t.  x + y <= 2, x, y in [-5, 1]. The optimum (1, 1), cost 2,
// is a degenerate vertex: the row and both upper bounds are active, and their multipliers
// are not unique (the row's lambda and each bound's 2 - lambda, any lambda in [0, 2]), so
// the interior point ends inside that face and its floor below the optimum.
Miqp DegenerateVertex() { return NearestPointBelowTheLine(2.0, 2.0, -5.0, 1.0); }

TEST(InteriorPointPolish, TheCrossoverRecoversTheExactOptimumAndAFloorEqualToIt) {
  const Miqp p = DegenerateVertex();
  const RelaxationResult plain = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  ASSERT_EQ(plain.status, RelaxationStatus::kSolved);
  EXPECT_EQ(plain.polished, 0);
  EXPECT_EQ(plain.polish_attempts, 0);
  // Without it: the optimum to the interior point's tolerance only.
  EXPECT_GT(std::abs(plain.x(0) - 1.0), 1e-12);
  EXPECT_LE(plain.CertifiedFloor(), 2.0);
  for (const double polish_tolerance : {1e-8, 1e-6, 1e-4}) {
    InteriorPointOptions options;
    options.polish_tolerance = polish_tolerance;
    const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
    ASSERT_EQ(r.status, RelaxationStatus::kSolved) << polish_tolerance;
    EXPECT_EQ(r.polished, 1) << polish_tolerance;
    EXPECT_EQ(r.x(0), 1.0);  // on its active bounds exactly
    EXPECT_EQ(r.x(1), 1.0);
    EXPECT_NEAR(r.objective, 2.0, 1e-13);
    EXPECT_NEAR(r.CertifiedFloor(), 2.0, 1e-13);
    EXPECT_LE(r.CertifiedFloor(), r.objective);
    // Reduced-cost rates from the bounds' side: x and y may only decrease from 1.
    EXPECT_EQ(r.lower_cost_rate(0), 0.0);
    EXPECT_GE(r.upper_cost_rate(0), 0.0);
    if (polish_tolerance > 1e-8) {
      EXPECT_LT(r.iterations, plain.iterations) << polish_tolerance;
    }
  }
}

// A polish from an equality row: min x^2 + y^2 s.t. x + y = 1, 0.8 <= x - y <= 2:
// x = 0.9, y = 0.1, cost 0.82, both sides of the equality active.
TEST(InteriorPointPolish, AnEqualityRowsMultiplierMayHaveEitherSign) {
  for (const double target : {1.0, -1.0}) {
    MiqpBuilder b;
    const int x = b.AddVariable("x", -3, 3, false), y = b.AddVariable("y", -3, 3, false);
    b.AddSquaredCost(LinExpr::Var(x), 1.0);
    b.AddSquaredCost(LinExpr::Var(y), 1.0);
    b.AddRow("eq", LinExpr::Var(x) + LinExpr::Var(y), target, target);
    b.AddRow("range", LinExpr::Var(x) - LinExpr::Var(y), 0.8, 2);
    const Miqp p = b.Build();
    InteriorPointOptions options;
    options.polish_tolerance = 1e-6;
    const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
    ASSERT_EQ(r.status, RelaxationStatus::kSolved);
    EXPECT_EQ(r.polished, 1) << target;
    // x = (target + 0.8) / 2, y = (target - 0.8) / 2.
    EXPECT_NEAR(r.x(0), 0.5 * (target + 0.8), 1e-13);
    EXPECT_NEAR(r.x(1), 0.5 * (target - 0.8), 1e-13);
    const double optimum = 0.25 * ((target + 0.8) * (target + 0.8) + (target - 0.8) * (target - 0.8));
    EXPECT_NEAR(r.objective, optimum, 1e-13);
    EXPECT_NEAR(r.CertifiedFloor(), optimum, 1e-13);
  }
}

// min (x - 0.5)^2 + (y - 0.5)^2  s.t.  x + y <= 2, x, y in [0, 2]: the optimum (0.5, 0.5),
// cost 0, leaves the row inactive.
Miqp InactiveRow() { return NearestPointBelowTheLine(0.5, 0.5, 0.0, 2.0); }

TEST(InteriorPointPolish, AWrongGuessIsRejectedAndItsFloorStaysBelowTheOptimum) {
  const Miqp p = InactiveRow();
  const double penalty = 1e6;
  const InequalityForm f = BuildInequalityForm(p, p.var_lower, p.var_upper, penalty);
  ASSERT_EQ(f.elastic, 1);
  // An iterate at the optimum whose row dual exceeds its slack: the row guessed active
  // (the guess reads only the slacks and duals; their mean product, 1e-3, keeps the bounds'
  // slacks above its square root, so the bounds are guessed inactive).
  Eigen::VectorXd w(3), s(6), z(6);
  w << 0.5, 0.5, 1e-9;
  s << 1e-2, 1e-9, 1.5, 0.5, 1.5, 0.5;  // row, e >= 0, (upper, lower) of x, of y
  z << 1e-1, penalty - 1e-1, 1e-3, 1e-3, 1e-3, 1e-3;
  ActiveSetPolishOptions one_solve;
  one_solve.max_rounds = 1;  // the guess alone, no correction
  const ActiveSetPolish wrong = PolishActiveSet(f, p, p.var_lower, p.var_upper, w, s, z, one_solve);
  EXPECT_FALSE(wrong.accepted);
  // The guess put x on the row (1, 1) with a negative multiplier, clipped to 0: the box
  // certificate still holds, far below the optimum 0.
  EXPECT_NEAR(wrong.x(0), 1.0, 1e-9);
  EXPECT_LE(wrong.floor, 0.0);
  EXPECT_NEAR(wrong.floor, 0.5 - 2.0, 1e-9);
  // With its correction rounds the row leaves the set (its multiplier is negative) and
  // the second solve is the optimum.
  const ActiveSetPolish corrected = PolishActiveSet(f, p, p.var_lower, p.var_upper, w, s, z, ActiveSetPolishOptions());
  EXPECT_TRUE(corrected.accepted);
  EXPECT_NEAR(corrected.x(0), 0.5, 1e-12);
  EXPECT_NEAR(corrected.floor, 0.0, 1e-12);
  // The right guess from the same point (the row's dual below its slack) is accepted.
  z(0) = 1e-4;
  const ActiveSetPolish right = PolishActiveSet(f, p, p.var_lower, p.var_upper, w, s, z, ActiveSetPolishOptions());
  EXPECT_TRUE(right.accepted);
  EXPECT_NEAR(right.objective, 0.0, 1e-15);
  EXPECT_NEAR(right.floor, 0.0, 1e-15);
}

// The solver with a crossover tried from an iterate far from the optimum (the loosest
// setting, no correction round): the wrong guess sends it on to its own convergence, to
// the same optimum, with a floor that still holds.
TEST(InteriorPointPolish, AFailedCrossoverFallsBackToTheInteriorPointsOwnAnswer) {
  MiqpBuilder b;
  std::vector<int> x;
  for (int j = 0; j < 6; ++j) x.push_back(b.AddVariable("x" + std::to_string(j), -1, 1, false));
  for (int j = 0; j < 6; ++j) b.AddSquaredCost(LinExpr::Var(x[j]) - LinExpr::Constant(0.3 * (j - 2)), 1.0 + j);
  for (int j = 0; j + 1 < 6; ++j) b.AddRow("r", LinExpr::Var(x[j]) + LinExpr::Var(x[j + 1]), -kInfinity, 0.2);
  const Miqp p = b.Build();
  const RelaxationResult plain = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  ASSERT_EQ(plain.status, RelaxationStatus::kSolved);
  InteriorPointOptions options;
  options.polish_tolerance = 0.9;  // the first iterates qualify
  options.polish.max_rounds = 1;   // and their guesses stand uncorrected
  const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  EXPECT_GE(r.polish_attempts, 1);
  // The first guess failed: either the second one (at convergence) finished, or none did.
  EXPECT_TRUE(r.polished == 0 || r.polish_attempts == 2) << r.polished << " " << r.polish_attempts;
  EXPECT_NEAR(r.objective, plain.objective, 1e-6 * (1.0 + std::abs(plain.objective)));
  EXPECT_LE(r.CertifiedFloor(), plain.objective + 1e-9);
  EXPECT_LE(r.CertifiedFloor(), r.objective);
}

}  // namespace
}  // namespace mfp
