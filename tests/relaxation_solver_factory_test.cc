// The factory's backends: the default hands a node mfp's interior point cannot solve to
// Ipopt (planner/qp/relaxation_solver_factory.h).
#include "planner/qp/relaxation_solver_factory.h"

#include <gtest/gtest.h>
#include "planner/qp/internal/ipm_relaxation_solver.h"
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

}  // namespace
}  // namespace mfp
