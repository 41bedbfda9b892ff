// The fixed-variable reduction every relaxation backend runs first: fixed variables move
// into the objective and the row bounds, rows the box already keeps are left out, and
// nodes that need no solver are settled directly.
#include "planner/qp/fixed_variable_reduction.h"

#include <gtest/gtest.h>

#include "planner/miqp/miqp_builder.h"

namespace mfp {
namespace {

// min (x - 2)^2 + (y - 1)^2  s.t.  x + y <= 2, x, y in [-5, 5].
Miqp Projection() {
  MiqpBuilder b;
  const int x = b.AddVariable("x", -5, 5, false), y = b.AddVariable("y", -5, 5, false);
  b.AddSquaredCost(LinExpr::Var(x) - LinExpr::Constant(2), 1.0);
  b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(1), 1.0);
  b.AddRow("sum", LinExpr::Var(x) + LinExpr::Var(y), -kInfinity, 2.0);
  return b.Build();
}

TEST(FixedVariableReduction, AFixedVariableMovesIntoTheRowBoundsAndTheObjective) {
  // x = 1: x + y <= 2 becomes y <= 1, and (x - 2)^2 becomes the constant 1.
  const Miqp p = Projection();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(0) = up(0) = 1.0;
  const ReducedQp reduced = ReduceFixedVariables(p, lo, up, 1e-9);
  EXPECT_FALSE(reduced.infeasible);
  ASSERT_EQ(reduced.free_index, std::vector<int>{1});
  ASSERT_EQ(reduced.problem.num_rows(), 1);
  EXPECT_NEAR(reduced.problem.row_upper(0), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(reduced.lower(0), -5.0);
  EXPECT_DOUBLE_EQ(reduced.upper(0), 5.0);
  // The reduced objective at y equals the original at (1, y), for any y.
  for (double y : {-2.0, 0.0, 0.7, 3.0}) {
    const Eigen::VectorXd full = reduced.Expand(Eigen::VectorXd::Constant(1, y));
    EXPECT_DOUBLE_EQ(full(0), 1.0);
    EXPECT_DOUBLE_EQ(full(1), y);
    EXPECT_NEAR(reduced.problem.Objective(Eigen::VectorXd::Constant(1, y)), p.Objective(full), 1e-12);
    EXPECT_DOUBLE_EQ(reduced.Restrict(full)(0), y);
  }
}

TEST(FixedVariableReduction, RowsTheBoxAlreadyKeepsAreLeftOut) {
  // y in [0, 2], x fixed to 1. Of the rows
  //   big_m:  y + 2x <= 5       -> y <= 3: the box keeps it, dropped
  //   loose:  y - x >= -5       -> y >= -4: dropped
  //   range:  0.5 <= y + x <= 10 -> -0.5 <= y <= 9: both sides kept by the box, dropped
  //   cap:    -3 <= y + x <= 2.5 -> y <= 1.5 binds; its lower side y >= -4 is left out
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 1, true), y = b.AddVariable("y", 0, 2, false);
  b.AddRow("big_m", LinExpr::Var(y) + LinExpr::Var(x, 2.0), -kInfinity, 5.0);
  b.AddRow("loose", LinExpr::Var(y) - LinExpr::Var(x), -5.0, kInfinity);
  b.AddRow("range", LinExpr::Var(y) + LinExpr::Var(x), 0.5, 10.0);
  b.AddRow("cap", LinExpr::Var(y) + LinExpr::Var(x), -3.0, 2.5);
  b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(2.0), 1.0);
  const Miqp p = b.Build();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(x) = up(x) = 1.0;
  const ReducedQp reduced = ReduceFixedVariables(p, lo, up, 1e-9);
  ASSERT_EQ(reduced.problem.num_rows(), 1);
  EXPECT_EQ(reduced.problem.row_lower(0), -kInfinity);
  EXPECT_NEAR(reduced.problem.row_upper(0), 1.5, 1e-15);
}

TEST(FixedVariableReduction, ARowTheFreeVariablesCannotMeetMakesTheNodeInfeasible) {
  // x fixed to 1.8 leaves y <= 0.2 in x + y <= 2, but y in [0.5, 5]: no solver needed.
  const Miqp p = Projection();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(0) = up(0) = 1.8;
  lo(1) = 0.5;
  EXPECT_TRUE(ReduceFixedVariables(p, lo, up, 1e-9).infeasible);
  ReducedQp reduced;
  RelaxationResult result;
  EXPECT_TRUE(ReduceOrSettle(p, lo, up, 1e-9, &reduced, &result));
  EXPECT_EQ(result.status, RelaxationStatus::kInfeasible);
}

TEST(FixedVariableReduction, NodesThatNeedNoSolverAreSettled) {
  const Miqp p = Projection();
  ReducedQp reduced;
  RelaxationResult result;
  // Crossed bounds.
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(1) = 1.0;
  up(1) = 0.0;
  EXPECT_TRUE(ReduceOrSettle(p, lo, up, 1e-9, &reduced, &result));
  EXPECT_EQ(result.status, RelaxationStatus::kInfeasible);
  // Everything fixed at a feasible point: solved, with the original objective there.
  lo = up = Eigen::Vector2d(0.5, 1.0);
  EXPECT_TRUE(ReduceOrSettle(p, lo, up, 1e-9, &reduced, &result));
  EXPECT_EQ(result.status, RelaxationStatus::kSolved);
  EXPECT_DOUBLE_EQ(result.objective, 2.25);  // (0.5 - 2)^2 + 0
  // Everything fixed off a row: infeasible.
  lo = up = Eigen::Vector2d(1.5, 1.0);
  EXPECT_TRUE(ReduceOrSettle(p, lo, up, 1e-9, &reduced, &result));
  EXPECT_EQ(result.status, RelaxationStatus::kInfeasible);
  // A free variable left: a QP for the solver.
  lo = p.var_lower;
  up = p.var_upper;
  EXPECT_FALSE(ReduceOrSettle(p, lo, up, 1e-9, &reduced, &result));
  EXPECT_EQ(reduced.free_index.size(), 2u);
}

}  // namespace
}  // namespace mfp
