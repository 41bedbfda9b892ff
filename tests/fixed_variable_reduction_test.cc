// The fixed-variable reduction every relaxation backend runs first: fixed variables move
// into the objective and the row bounds, rows the box already keeps are left out, and
// nodes that need no solver are settled directly.
#include "planner/qp/internal/fixed_variable_reduction.h"

#include <gtest/gtest.h>

#include "tests/test_qps.h"

namespace mfp {
namespace {

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
  // x fixed to 1: big_m, loose and range are kept by y's box; of cap only y <= 1.5 is left.
  const Miqp p = RowsTheBoxMostlyKeeps();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(0) = up(0) = 1.0;
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
