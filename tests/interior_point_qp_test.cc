// mfp's interior-point QP on problems solved by hand.
#include "planner/qp/interior_point_qp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>

#include "planner/miqp/miqp_builder.h"
#include "planner/qp/internal/fixed_variable_reduction.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/qp/internal/ipopt_relaxation_solver.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_qps.h"

namespace mfp {
namespace {

TEST(InteriorPointQp, ProjectionOntoAHalfPlane) {
  const Miqp p = Projection();
  const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  // Converged to the relative tolerances: the objective to 1e-8, the point to ~1e-5.
  EXPECT_NEAR(r.x(0), 1.5, 2e-5);
  EXPECT_NEAR(r.x(1), 0.5, 2e-5);
  EXPECT_NEAR(r.objective, 0.5, 1e-8);
  EXPECT_LT(r.iterations, 30);
}

// A random convex QP with box bounds and one-sided rows that the middle of the box
// meets (so it is feasible): min sum_j (x_j - t_j)^2 + c'x over x in [-1, 1]^n,
// a_k'x <= b_k. Deterministic (fixed seed).
Miqp RandomFeasibleQp(int n, int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MiqpBuilder b;
  std::vector<int> x;
  for (int j = 0; j < n; ++j) x.push_back(b.AddVariable("x" + std::to_string(j), -1, 1, false));
  for (int j = 0; j < n; ++j) {
    b.AddSquaredCost(LinExpr::Var(x[j]) - LinExpr::Constant(2.0 * u(rng)), 1.0);
    b.AddLinearCost(LinExpr::Var(x[j], 0.1 * u(rng)));
  }
  for (int k = 0; k < rows; ++k) {
    LinExpr row;
    for (int j = 0; j < n; ++j) {
      if (u(rng) > 0.6) row += LinExpr::Var(x[j], u(rng));
    }
    b.AddRow("r" + std::to_string(k), row, -kInfinity, 0.2 + 0.3 * (u(rng) + 1.0));
  }
  return b.Build();
}

TEST(InteriorPointQp, AWarmStartFromTheParentsPointConvergesToTheSameOptimumSooner) {
  const Miqp p = RandomFeasibleQp(40, 60, 7);
  const InteriorPointOptions options;
  const RelaxationResult cold = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
  ASSERT_EQ(cold.status, RelaxationStatus::kSolved);
  // From its own solution: the same optimum, in fewer iterations. (The objective at
  // convergence is known to about the number of inequalities times the final average
  // complementarity, 1e-8 relative each: 1e-5 relative here, whatever the start.)
  const double accuracy = 1e-5 * (1.0 + std::abs(cold.objective));
  const RelaxationResult again = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, &cold.x, options);
  ASSERT_EQ(again.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(again.objective, cold.objective, accuracy);
  EXPECT_LT(again.iterations, cold.iterations);
  // A child, as branching makes one: a variable's box cut below the parent's value. Warm
  // from the parent's point (now outside the box), the child's optimum is the cold one.
  int j = 0;
  while (j < p.num_variables() && cold.x(j) < -0.5) ++j;
  ASSERT_LT(j, p.num_variables());
  Eigen::VectorXd upper = p.var_upper;
  upper(j) = cold.x(j) - 0.5;
  const RelaxationResult child_cold = SolveQpInteriorPoint(p, p.var_lower, upper, nullptr, options);
  const RelaxationResult child_warm = SolveQpInteriorPoint(p, p.var_lower, upper, &cold.x, options);
  ASSERT_EQ(child_cold.status, RelaxationStatus::kSolved);
  ASSERT_EQ(child_warm.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(child_warm.objective, child_cold.objective, accuracy);
  EXPECT_LE(child_warm.x(j), upper(j) + 1e-9);
}

TEST(InteriorPointQp, AWarmStartStillFindsAnInfeasibleChild) {
  // x + y >= 1.5 with x, y <= 0.7 after branching: infeasible, whatever the start.
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 1, false), y = b.AddVariable("y", 0, 1, false);
  b.AddRow("demand", LinExpr::Var(x) + LinExpr::Var(y), 1.5, kInfinity);
  b.AddSquaredCost(LinExpr::Var(x) - LinExpr::Var(y), 1.0);
  const Miqp p = b.Build();
  const RelaxationResult parent = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  ASSERT_EQ(parent.status, RelaxationStatus::kSolved);
  Eigen::VectorXd upper = p.var_upper;
  upper << 0.7, 0.7;
  for (double tolerance : {1e-8, 1e-6}) {
    InteriorPointOptions options;
    options.tolerance = tolerance;
    EXPECT_EQ(SolveQpInteriorPoint(p, p.var_lower, upper, &parent.x, options).status, RelaxationStatus::kInfeasible)
        << tolerance;
  }
}

TEST(InteriorPointQp, TheIntervalChainIsSolvedOrReportedUnsolved) {
  // The chain's big-M rows (test_qps.h) spread its binaries' weight. mfp's interior
  // point does not converge on its relaxation (issue 26, docs/measurements.md): it must
  // say so, never a wrong "solved", and the default backend gives Ipopt's answer.
  for (const int feet : {1, 10}) {
    const Miqp p = IntervalChain(feet);
    const RelaxationResult ipopt = MakeIpoptRelaxationSolver()->Solve(p, RelaxationRequest());
    ASSERT_EQ(ipopt.status, RelaxationStatus::kSolved);
    const RelaxationResult own = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
    if (own.status == RelaxationStatus::kSolved) {
      EXPECT_NEAR(own.objective, ipopt.objective, 1e-6 * std::abs(ipopt.objective)) << feet << " feet";
    } else {
      EXPECT_EQ(own.status, RelaxationStatus::kIterationLimit) << feet << " feet";
    }
    const RelaxationResult r =
        MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback)->Solve(p, RelaxationRequest());
    ASSERT_EQ(r.status, RelaxationStatus::kSolved);
    EXPECT_EQ(r.fallbacks, own.status == RelaxationStatus::kSolved ? 0 : 1);
    EXPECT_NEAR(r.objective, ipopt.objective, 1e-6 * std::abs(ipopt.objective)) << feet << " feet";
  }
}

TEST(InteriorPointQp, CutoffStopsOnceAProvenFloorReachesIt) {
  const Miqp p = Projection();  // optimum 0.5
  const RelaxationResult full = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  InteriorPointOptions options;
  options.cutoff = 0.4;  // below the optimum: provable before convergence
  const RelaxationResult cut = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
  ASSERT_EQ(cut.status, RelaxationStatus::kCutoff);
  EXPECT_GE(cut.objective, 0.4);
  EXPECT_LE(cut.objective, 0.5 + 1e-12);  // a floor: never above the optimum
  EXPECT_LT(cut.iterations, full.iterations);
  options.cutoff = 0.5 + 1e-3;  // above the optimum: solved to the end
  const RelaxationResult solved = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
  ASSERT_EQ(solved.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(solved.objective, 0.5, 1e-8);

  // Through the solver interface the cutoff holds for its own request only.
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  RelaxationRequest cut_request;
  cut_request.cutoff = 0.4;
  EXPECT_EQ(solver->Solve(p, cut_request).status, RelaxationStatus::kCutoff);
  const RelaxationResult next = solver->Solve(p, RelaxationRequest());
  ASSERT_EQ(next.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(next.objective, 0.5, 1e-8);
}

TEST(InteriorPointQp, ALooserToleranceHoldsForItsOwnRequestOnly) {
  const Miqp p = Projection();  // optimum 0.5
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  const RelaxationResult exact = solver->Solve(p, RelaxationRequest());
  RelaxationRequest loose;
  loose.relative_tolerance = 1e-3;
  const RelaxationResult coarse = solver->Solve(p, loose);
  ASSERT_EQ(coarse.status, RelaxationStatus::kSolved);
  EXPECT_LT(coarse.iterations, exact.iterations);
  EXPECT_NEAR(coarse.objective, 0.5, 1e-2);
  const RelaxationResult next = solver->Solve(p, RelaxationRequest());
  EXPECT_EQ(next.iterations, exact.iterations);
  EXPECT_NEAR(next.objective, 0.5, 1e-8);
  RelaxationRequest tight;
  tight.relative_tolerance = 1e-12;  // tighter than the solver's own: its own holds
  EXPECT_EQ(solver->Solve(p, tight).iterations, exact.iterations);
}

TEST(InteriorPointQp, LinearProgramWithActiveBounds) {
  // min -x - 2y s.t. x + y <= 1.5, x, y in [0, 1]: y = 1, x = 0.5, objective -2.5.
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 1, false), y = b.AddVariable("y", 0, 1, false);
  b.AddRow("cap", LinExpr::Var(x) + LinExpr::Var(y), -kInfinity, 1.5);
  b.AddLinearCost(LinExpr::Var(x, -1) + LinExpr::Var(y, -2));
  const Miqp p = b.Build();
  const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(r.objective, -2.5, 1e-6);
  EXPECT_NEAR(r.x(1), 1.0, 1e-6);
}

TEST(InteriorPointQp, EqualityAndRangedRows) {
  // min x^2 + y^2 s.t. x + y = 1, 0.8 <= x - y <= 2: x = 0.9, y = 0.1, cost 0.82.
  MiqpBuilder b;
  const int x = b.AddVariable("x", -3, 3, false), y = b.AddVariable("y", -3, 3, false);
  b.AddSquaredCost(LinExpr::Var(x), 1.0);
  b.AddSquaredCost(LinExpr::Var(y), 1.0);
  b.AddRow("eq", LinExpr::Var(x) + LinExpr::Var(y), 1, 1);
  b.AddRow("range", LinExpr::Var(x) - LinExpr::Var(y), 0.8, 2);
  const Miqp p = b.Build();
  const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(r.x(0), 0.9, 1e-6);
  EXPECT_NEAR(r.x(1), 0.1, 1e-6);
  EXPECT_NEAR(r.objective, 0.82, 1e-6);
}

TEST(InteriorPointQp, InfeasibleRowsAreReportedNotSolved) {
  // x + y >= 3 with x, y in [0, 1] cannot hold; the elastic rows end positive.
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 1, false), y = b.AddVariable("y", 0, 1, false);
  b.AddRow("need", LinExpr::Var(x) + LinExpr::Var(y), 3, kInfinity);
  b.AddSquaredCost(LinExpr::Var(x), 1.0);
  const Miqp p = b.Build();
  const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  EXPECT_EQ(r.status, RelaxationStatus::kInfeasible);
}

TEST(InteriorPointQp, ABoxNarrowerThanRoundingErrorIsAFixedVariable) {
  // Bound propagation can leave a variable a box one ulp wide. Kept free, its bound
  // duals grew without limit and the interior point hit its iteration limit (every
  // such node then went to Ipopt). Treated as fixed, the node solves at once:
  // x = 0.3 leaves min (y - 1)^2 + 1.7^2 with y <= 1.7, so y = 1 and the cost is 2.89.
  const Miqp p = Projection();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(0) = 0.3;
  up(0) = std::nextafter(0.3, 1.0);
  const ReducedQp reduced = ReduceFixedVariables(p, lo, up, 1e-9);
  EXPECT_EQ(reduced.free_index.size(), 1u);
  EXPECT_GE(reduced.fixed_x(0), lo(0));
  EXPECT_LE(reduced.fixed_x(0), up(0));
  const Eigen::VectorXd warm = Eigen::Vector2d(0.3, 0.9);
  for (const Eigen::VectorXd& start : {Eigen::VectorXd(), warm}) {
    RelaxationRequest request;
    request.lower = lo;
    request.upper = up;
    request.warm_start = start;
    const RelaxationResult r = MakeInteriorPointRelaxationSolver()->Solve(p, request);
    ASSERT_EQ(r.status, RelaxationStatus::kSolved);
    EXPECT_NEAR(r.x(1), 1.0, 1e-4);
    EXPECT_NEAR(r.objective, 1.7 * 1.7, 1e-6);
  }
}

TEST(InteriorPointQp, SolvesANodeWhoseOnlyRowLeftBinds) {
  // x fixed to 1 by the node: only cap's upper side reaches the solver (the reduction,
  // fixed_variable_reduction_test.cc), and min (y - 2)^2 ends on it at y = 1.5.
  const Miqp p = RowsTheBoxMostlyKeeps();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(0) = up(0) = 1.0;
  RelaxationRequest request;
  request.lower = lo;
  request.upper = up;
  const RelaxationResult r = MakeInteriorPointRelaxationSolver()->Solve(p, request);
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(r.x(1), 1.5, 1e-6);
  EXPECT_NEAR(r.objective, 0.25, 1e-6);
}

TEST(InteriorPointQp, ReducedCostCertificateHoldsAtEveryFeasiblePoint) {
  // min (a - 0.2)^2 + 3 (b - 0.9)^2 - 2 c  s.t.  a + b + c <= 1.6, a - b >= -0.5,
  // a, b, c in [0, 1]. The relaxation's certificate must bound the objective from below
  // at every point of the box that meets the rows: checked on 20000 sampled points.
  MiqpBuilder bld;
  const int a = bld.AddVariable("a", 0, 1, false), b = bld.AddVariable("b", 0, 1, false),
            c = bld.AddVariable("c", 0, 1, false);
  bld.AddRow("sum", LinExpr::Var(a) + LinExpr::Var(b) + LinExpr::Var(c), -kInfinity, 1.6);
  bld.AddRow("diff", LinExpr::Var(a) - LinExpr::Var(b), -0.5, kInfinity);
  bld.AddSquaredCost(LinExpr::Var(a) - LinExpr::Constant(0.2), 1.0);
  bld.AddSquaredCost(LinExpr::Var(b) - LinExpr::Constant(0.9), 3.0);
  bld.AddLinearCost(LinExpr::Var(c, -2.0));
  const Miqp p = bld.Build();
  const RelaxationResult r = MakeInteriorPointRelaxationSolver()->Solve(p, RelaxationRequest());
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  ASSERT_EQ(r.lower_cost_rate.size(), 3);
  ASSERT_EQ(r.upper_cost_rate.size(), 3);
  EXPECT_LE(r.cost_floor, r.objective);
  EXPECT_GT(r.cost_floor, r.objective - 1e-6);
  // c sits at its upper bound with a positive rate: lowering it must cost.
  EXPECT_GT(r.upper_cost_rate(c), 0.1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    Eigen::VectorXd x(3);
    x << unit(rng), unit(rng), unit(rng);
    if (p.MaxViolation(x) > 0.0) continue;
    ++checked;
    double floor = r.cost_floor;
    for (int j = 0; j < 3; ++j) {
      floor += r.lower_cost_rate(j) * (x(j) - p.var_lower(j)) + r.upper_cost_rate(j) * (p.var_upper(j) - x(j));
    }
    ASSERT_GE(p.Objective(x), floor - 1e-9) << x.transpose();
  }
  EXPECT_GT(checked, 1000);
}


TEST(InteriorPointQp, WithoutRefinementTheSameOptimaAndFloorsThatHoldBelowThem) {
  // No refinement changes the Newton directions' accuracy, not what convergence asks of
  // the iterate: the same optimum to the tolerance, and the floor still below it, cold
  // and warm-started from a parent with one bound moved.
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const Miqp p = RandomFeasibleQp(60, 40, seed);
    InteriorPointOptions refined, plain;
    plain.refinement_steps = plain.predictor_refinement_steps = 0;
    const RelaxationResult a = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, refined);
    const RelaxationResult b = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, plain);
    ASSERT_EQ(a.status, RelaxationStatus::kSolved) << seed;
    ASSERT_EQ(b.status, RelaxationStatus::kSolved) << seed;
    const double scale = 1.0 + std::abs(a.objective);
    EXPECT_NEAR(b.objective, a.objective, 1e-6 * scale) << seed;
    EXPECT_LE(b.cost_floor, a.objective + 1e-9 * scale) << seed;
    EXPECT_LE(a.cost_floor, b.objective + 1e-9 * scale) << seed;
    // A child: the first variable's upper bound moved to the middle of its box.
    Eigen::VectorXd upper = p.var_upper;
    upper(0) = 0.5 * (p.var_lower(0) + p.var_upper(0));
    const RelaxationResult ca = SolveQpInteriorPoint(p, p.var_lower, upper, &a.x, refined);
    const RelaxationResult cb = SolveQpInteriorPoint(p, p.var_lower, upper, &a.x, plain);
    ASSERT_EQ(ca.status, cb.status) << seed;
    if (ca.status != RelaxationStatus::kSolved) continue;
    EXPECT_NEAR(cb.objective, ca.objective, 1e-6 * (1.0 + std::abs(ca.objective))) << seed;
    EXPECT_LE(cb.cost_floor, ca.objective + 1e-9 * (1.0 + std::abs(ca.objective))) << seed;
  }
}

TEST(InteriorPointQp, EveryRefinementSettingKeepsFloorsAndCutoffsBelowAReferenceOptimum) {
  // Whatever the Newton solves' refinement (none, the predictor's or the corrector's
  // alone, both), a solved node's floor and a cut-off node's objective lie below the
  // optimum, here Ipopt's at 1e-10 (whose bounds are relaxed by ~1e-8: if anything below
  // the true optimum), cold and from warm starts as a search branches. The objectives
  // agree with the fully refined solve's to 1e-7 and with Ipopt's to 1e-5: the
  // convergence rule accepts a dual residual of acceptable_dual once complementarity is
  // tiny, which leaves the objective a few 1e-6 above the optimum on these QPs.
  IpoptSettings tight;
  tight.tolerance = 1e-10;
  const auto ipopt = MakeIpoptRelaxationSolver(tight);
  const std::pair<int, int> settings[] = {{0, 0}, {0, 1}, {1, 0}, {2, 2}};  // (predictor, corrector)
  int checked = 0;  // cases Ipopt solved, so compared
  for (unsigned seed = 21; seed <= 28; ++seed) {
    const Miqp p = RandomFeasibleQp(50, 45, seed);
    const RelaxationResult parent = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
    ASSERT_EQ(parent.status, RelaxationStatus::kSolved) << seed;
    for (int child = 0; child < 3; ++child) {
      Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
      if (child == 1) upper(seed % 50) = parent.x(seed % 50) - 0.3;
      if (child == 2) lower(seed % 50) = parent.x(seed % 50) + 0.3;
      RelaxationRequest request;
      request.lower = lower;
      request.upper = upper;
      const RelaxationResult reference = ipopt->Solve(p, request);
      if (reference.status != RelaxationStatus::kSolved) continue;
      ++checked;
      const double scale = 1.0 + std::abs(reference.objective);
      const Eigen::VectorXd* warm = child == 0 ? nullptr : &parent.x;
      InteriorPointOptions refined;
      refined.predictor_refinement_steps = refined.refinement_steps = 2;
      const RelaxationResult full = SolveQpInteriorPoint(p, lower, upper, warm, refined);
      ASSERT_EQ(full.status, RelaxationStatus::kSolved) << seed << " " << child;
      for (const auto& [predictor, corrector] : settings) {
        InteriorPointOptions options;
        options.predictor_refinement_steps = predictor;
        options.refinement_steps = corrector;
        const RelaxationResult r = SolveQpInteriorPoint(p, lower, upper, warm, options);
        ASSERT_EQ(r.status, RelaxationStatus::kSolved) << seed << " " << child << " " << predictor << corrector;
        EXPECT_NEAR(r.objective, full.objective, 1e-7 * scale) << seed << " " << child;
        EXPECT_NEAR(r.objective, reference.objective, 1e-5 * scale) << seed << " " << child;
        EXPECT_LE(r.cost_floor, reference.objective + 1e-9 * scale) << seed << " " << child;
        // A cutoff a hair below the optimum: either proven (its floor below the optimum)
        // or solved to the end.
        options.cutoff = reference.objective - 1e-5 * scale;
        const RelaxationResult cut = SolveQpInteriorPoint(p, lower, upper, warm, options);
        if (cut.status == RelaxationStatus::kCutoff) {
          EXPECT_GE(cut.objective, options.cutoff) << seed << " " << child;
          EXPECT_LE(cut.objective, reference.objective + 1e-9 * scale) << seed << " " << child;
        } else {
          EXPECT_EQ(cut.status, RelaxationStatus::kSolved) << seed << " " << child;
        }
      }
    }
  }
  EXPECT_GE(checked, 12) << "too few cases had a reference optimum to compare with";
}

TEST(InteriorPointQp, AQpOverTheKktWorkBudgetIsRefusedBeforeAssemblyAndNotHandedOn) {
  // 60 variables in rows of ~24 each: ~12,000 product terms.
  const Miqp p = RandomFeasibleQp(60, 40, 3);
  InteriorPointOptions small;
  small.max_kkt_terms = 1000;
  const RelaxationResult refused = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, small);
  EXPECT_EQ(refused.status, RelaxationStatus::kFailed);
  EXPECT_TRUE(refused.over_work_budget);
  EXPECT_EQ(refused.iterations, 0);
  const RelaxationResult solved = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, InteriorPointOptions());
  EXPECT_EQ(solved.status, RelaxationStatus::kSolved);
  EXPECT_FALSE(solved.over_work_budget);
}

TEST(InteriorPointQp, AStopFlagSetBeforeTheSolveEndsItBeforeAnyIteration) {
  const Miqp p = RandomFeasibleQp(600, 400, 4);
  std::atomic<bool> stop{true};
  InteriorPointOptions stopped;
  stopped.deadline = Deadline().WithStop(&stop);
  const RelaxationResult r = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, stopped);
  EXPECT_EQ(r.status, RelaxationStatus::kIterationLimit);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.x.size(), 600);
}

}  // namespace
}  // namespace mfp
