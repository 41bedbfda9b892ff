// Bound propagation over the rows of an MIQP, on problems solved by hand.
#include "planner/search/internal/bound_propagation.h"

#include <gtest/gtest.h>

#include "planner/miqp/miqp_builder.h"

namespace mfp {
namespace {

TEST(BoundPropagation, TightensAndDetectsInfeasibility) {
  // x + y <= 1 with y >= 0.75 gives x <= 0.25; with x integer in [0, 3], x = 0.
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 3, true), y = b.AddVariable("y", 0.75, 2, false);
  b.AddRow("cap", LinExpr::Var(x) + LinExpr::Var(y), -kInfinity, 1.0);
  const Miqp p = b.Build();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  const PropagationResult r = PropagateBounds(p, &lo, &up);
  EXPECT_FALSE(r.infeasible);
  EXPECT_EQ(up(0), 0.0);
  // Derived continuous bounds are kept the tolerance (1e-7, relative) outward.
  EXPECT_GE(up(1), 1.0);
  EXPECT_NEAR(up(1), 1.0, 1e-6);
  // With y >= 1.5 nothing fits.
  lo = p.var_lower;
  up = p.var_upper;
  lo(1) = 1.5;
  EXPECT_TRUE(PropagateBounds(p, &lo, &up).infeasible);
}

TEST(BoundPropagation, ATinyCoefficientBoundsNothing) {
  // y - 1e-17 x <= 0.3 with y >= 0.3 + 1e-12: met within the tolerance. Solving the row
  // for x divides a rounding-sized excess by 1e-17 and would demand x >= 1e5, outside
  // [-1, 1]: a false infeasibility (as a hull edge normal with a 6e-17 component once
  // gave). Such a coefficient is skipped; y's bound is still derived and checked.
  MiqpBuilder b;
  const int x = b.AddVariable("x", -1, 1, false), y = b.AddVariable("y", 0.3 + 1e-12, 2, false);
  b.AddRow("edge", LinExpr::Var(y) - LinExpr::Var(x, 1e-17), -kInfinity, 0.3);
  const Miqp p = b.Build();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  const PropagationResult r = PropagateBounds(p, &lo, &up);
  EXPECT_FALSE(r.infeasible);
  EXPECT_EQ(lo(x), -1.0);
  EXPECT_EQ(up(x), 1.0);
  EXPECT_GE(up(y), 0.3);  // kept the tolerance outward
  EXPECT_NEAR(up(y), 0.3, 1e-6);
}

TEST(BoundPropagation, KeepsAPointThatMeetsTheRowsExactly) {
  // 3 x <= 0.3 and x >= 0.1 (a foot on its region's edge, held there by a trimmed step):
  // x = 0.1 meets both, but 0.3 / 3 rounds to 0.09999999999999999. A bound derived that
  // way cut the point off, and the relaxation with x fixed at 0.1 became infeasible.
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 1, false);
  b.AddRow("edge", LinExpr::Var(x, 3.0), -kInfinity, 0.3);
  b.AddRow("held", LinExpr::Var(x), 0.1, kInfinity);
  const Miqp p = b.Build();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  const PropagationResult r = PropagateBounds(p, &lo, &up);
  EXPECT_FALSE(r.infeasible);
  EXPECT_LE(lo(x), 0.1);
  EXPECT_GE(up(x), 0.1);
  EXPECT_LT(up(x), 0.1 + 1e-6);
}

}  // namespace
}  // namespace mfp
