// The factory's backends: the default hands a node mfp's interior point cannot solve to
// Ipopt (planner/qp/relaxation_solver_factory.h).
#include "planner/qp/relaxation_solver_factory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "planner/qp/internal/fallback_relaxation_solver.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/qp/internal/ipopt_relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_qps.h"

namespace mfp {
namespace {

TEST(RelaxationSolverFactory, DegenerateNodesFallBackToIpopt) {
  // Fixing x = 1 in the projection problem leaves y <= 1 and min (y - 1)^2 + 1: the
  // optimum y = 1 sits on the row with a zero multiplier (no strict complementarity).
  // mfp's interior point may not converge on such a degenerate node; it must then say
  // so (never a wrong "solved"), and the default backend hands the node to Ipopt.
  const Miqp p = Projection();
  Eigen::VectorXd lo = p.var_lower, up = p.var_upper;
  lo(0) = up(0) = 1.0;  // the reduction leaves y <= 1 (fixed_variable_reduction_test.cc)
  RelaxationRequest request;
  request.lower = lo;
  request.upper = up;
  const RelaxationResult own = MakeInteriorPointRelaxationSolver()->Solve(p, request);
  if (own.status == RelaxationStatus::kSolved) {
    EXPECT_NEAR(own.objective, 1.0, 1e-6);
  } else {
    EXPECT_EQ(own.status, RelaxationStatus::kIterationLimit);
  }
  const RelaxationResult r =
      MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback)->Solve(p, request);
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  // The objective grows with (y - 1)^2 only, so an objective accurate to 1e-8 places y
  // to about its square root: the bound the search uses is the objective.
  EXPECT_NEAR(r.x(1), 1.0, 1e-3);
  EXPECT_LE(r.x(1), 1.0 + 1e-6);  // and never beyond the row
  EXPECT_NEAR(r.objective, 1.0, 1e-6);
}

// An interior point cut off after two iterations: it cannot finish any of these QPs.
std::unique_ptr<RelaxationSolver> TwoIterationIpm() {
  InteriorPointOptions options;
  options.max_iterations = 2;
  return MakeInteriorPointRelaxationSolver(options);
}

TEST(RelaxationSolverFactory, AQpThePrimaryCannotFinishIsAStatusAndFallsBack) {
  const Miqp p = Projection();  // optimum 0.5
  const RelaxationResult own = TwoIterationIpm()->Solve(p, RelaxationRequest());
  EXPECT_EQ(own.status, RelaxationStatus::kIterationLimit);
  EXPECT_EQ(own.fallbacks, 0);
  const auto solver = MakeFallbackRelaxationSolver(TwoIterationIpm(), MakeIpoptRelaxationSolver());
  const RelaxationResult r = solver->Solve(p, RelaxationRequest());
  ASSERT_EQ(r.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(r.objective, 0.5, 1e-6);
  EXPECT_EQ(r.fallbacks, 1);
  EXPECT_GT(r.fallback_time_s, 0.0);
  // The default backend's interior point finishes it itself.
  const RelaxationResult own_default =
      MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback)->Solve(p, RelaxationRequest());
  ASSERT_EQ(own_default.status, RelaxationStatus::kSolved);
  EXPECT_EQ(own_default.fallbacks, 0);
}

TEST(RelaxationSolverFactory, TheSearchCountsItsFallbacks) {
  BranchAndBoundOptions options;
  options.time_limit_s = 30.0;
  const Miqp chain = IntervalChain(3);
  const auto falling = MakeFallbackRelaxationSolver(TwoIterationIpm(), MakeIpoptRelaxationSolver());
  const BranchAndBoundResult fell = SolveBranchAndBound(chain, *falling, options);
  ASSERT_EQ(fell.status, SolveStatus::kOptimal);
  EXPECT_GE(fell.node_fallbacks, 1);  // the root at least
  EXPECT_LE(fell.node_fallbacks, fell.nodes);
  EXPECT_GE(fell.fallbacks, fell.node_fallbacks);
  EXPECT_LE(fell.fallbacks, fell.relaxations);
  EXPECT_GT(fell.fallback_time_s, 0.0);
  // Ipopt alone: the same optimum, and no fallback counted.
  const auto ipopt = MakeIpoptRelaxationSolver();
  const BranchAndBoundResult alone = SolveBranchAndBound(chain, *ipopt, options);
  ASSERT_EQ(alone.status, SolveStatus::kOptimal);
  EXPECT_EQ(alone.fallbacks, 0);
  EXPECT_EQ(alone.fallback_time_s, 0.0);
  EXPECT_NEAR(alone.objective, fell.objective, 1e-4 * std::max(1.0, std::abs(fell.objective)));
}

}  // namespace
}  // namespace mfp
