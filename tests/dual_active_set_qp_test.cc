// mfp's dual active-set QP against the interior point: random convex QPs with a
// singular Hessian, sequences of branch-and-bound-like bound changes (warm starts),
// infeasible nodes (certified by the dual method, never a feasible one), the root relaxations of Table I instances, and children started from
// their parent's active set (warm tokens).
#include "planner/qp/dual_active_set_qp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_qps.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

// A convex QP whose Hessian is singular, as the planner's are: chained squared
// differences of the continuous variables (constant shifts cost nothing), binaries in
// [0, 1] with no quadratic cost, two-sided and equality rows met by a random point of the
// box (so it is feasible).
Miqp RandomSingularQp(int n, int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MiqpBuilder b;
  std::vector<int> x;
  Eigen::VectorXd point(n);
  for (int j = 0; j < n; ++j) {
    const bool binary = j % 3 == 2;
    x.push_back(binary ? b.AddBinary("b" + std::to_string(j)) : b.AddVariable("x" + std::to_string(j), -3, 3, false));
    point(j) = binary ? 0.5 * (u(rng) + 1.0) : 2.0 * u(rng);
  }
  for (int j = 0; j + 1 < n; ++j) {
    b.AddSquaredCost(LinExpr::Var(x[j + 1]) - LinExpr::Var(x[j]) - LinExpr::Constant(u(rng)), 1.0 + u(rng));
    b.AddLinearCost(LinExpr::Var(x[j], 0.3 * u(rng)));
  }
  for (int k = 0; k < rows; ++k) {
    LinExpr row;
    double at_point = 0.0;
    for (int j = 0; j < n; ++j) {
      if (u(rng) > 0.7) {
        const double a = u(rng);
        row += LinExpr::Var(x[j], a);
        at_point += a * point(j);
      }
    }
    if (k == 0) {
      b.AddRow("eq", row, at_point, at_point);
    } else {
      b.AddRow("r" + std::to_string(k), row, k % 2 ? -kInfinity : at_point - 0.5, at_point + 0.1 * (u(rng) + 1.0));
    }
  }
  return b.Build();
}

RelaxationResult Ipm(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  RelaxationRequest request;
  request.lower = lower;
  request.upper = upper;
  return MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback)->Solve(p, request);
}

// The two agree on the optimum to 1e-6 relative, and the dual active set's cost floor
// (with its reduced costs) is a true floor: at most the interior point's objective.
void ExpectAgrees(const Miqp& p, const RelaxationResult& dual, const RelaxationResult& ipm) {
  ASSERT_EQ(ipm.status, RelaxationStatus::kSolved);
  ASSERT_EQ(dual.status, RelaxationStatus::kSolved);
  const double scale = 1.0 + std::abs(ipm.objective);
  EXPECT_NEAR(dual.objective, ipm.objective, 1e-5 * scale);
  EXPECT_LE(dual.cost_floor, ipm.objective + 1e-7 * scale);
  EXPECT_GE(dual.cost_floor, ipm.objective - 1e-4 * scale);
  EXPECT_LE(p.MaxViolationOfRows(dual.x), 1e-6);
  ASSERT_EQ(dual.lower_cost_rate.size(), p.num_variables());
  EXPECT_GE(dual.lower_cost_rate.minCoeff(), 0.0);
  EXPECT_GE(dual.upper_cost_rate.minCoeff(), 0.0);
}

TEST(DualActiveSetQp, AgreesWithTheInteriorPointOnRandomSingularQps) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE(seed);
    const Miqp p = RandomSingularQp(30 + 5 * static_cast<int>(seed), 40, seed);
    DualActiveSetQp qp;
    const RelaxationResult dual = qp.Solve(p, p.var_lower, p.var_upper, kInfinity, Deadline());
    ExpectAgrees(p, dual, Ipm(p, p.var_lower, p.var_upper));
  }
}

TEST(DualActiveSetQp, WarmStartsAlongADiveAndAfterJumpsMatchTheInteriorPoint) {
  // Branch-and-bound-like: each node fixes one more binary of its parent's (a dive), and
  // every fourth node jumps back to the root's box with one other fixing (bounds loosen).
  const Miqp p = RandomSingularQp(60, 50, 42);
  DualActiveSetQp qp;
  std::mt19937 rng(3);
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  int compared = 0;
  for (int node = 0; node < 24; ++node) {
    SCOPED_TRACE(node);
    if (node % 4 == 3) {
      lower = p.var_lower;
      upper = p.var_upper;
    }
    const int j = 3 * static_cast<int>(rng() % 20) + 2;
    (rng() % 2 ? lower(j) : upper(j)) = rng() % 2 ? 1.0 : 0.0;
    if (lower(j) > upper(j)) std::swap(lower(j), upper(j));
    const RelaxationResult ipm = Ipm(p, lower, upper);
    const RelaxationResult dual = qp.Solve(p, lower, upper, kInfinity, Deadline());
    if (ipm.status == RelaxationStatus::kInfeasible) {
      EXPECT_NE(dual.status, RelaxationStatus::kSolved);
      continue;
    }
    ExpectAgrees(p, dual, ipm);
    ++compared;
  }
  EXPECT_GE(compared, 12);
}

TEST(DualActiveSetQp, AnInfeasibleNodeIsCertifiedInfeasibleAndTheFactoryCallsItInfeasible) {
  // x + y <= 2 with x, y >= 1.5: no point. The dual method finds the row dependent on the
  // two active bounds and checks the certificate; the factory's chain says the same.
  const Miqp p = Projection();
  Eigen::VectorXd lower = p.var_lower;
  lower << 1.5, 1.5;
  DualActiveSetQp qp;
  const RelaxationResult dual = qp.Solve(p, lower, p.var_upper, kInfinity, Deadline());
  EXPECT_EQ(dual.status, RelaxationStatus::kInfeasible);
  // Barely feasible (x = y = 1 meets x + y <= 2 with equality): never called infeasible.
  Eigen::VectorXd touching = p.var_lower;
  touching << 1.0, 1.0;
  EXPECT_EQ(qp.Solve(p, touching, p.var_upper, kInfinity, Deadline()).status, RelaxationStatus::kSolved);
  RelaxationRequest request;
  request.lower = lower;
  const RelaxationResult chained = MakeRelaxationSolver(RelaxationBackend::kDualActiveSetWithFallbacks)->Solve(p, request);
  EXPECT_EQ(chained.status, RelaxationStatus::kInfeasible);
  // The same solver object then solves the feasible box again (its factors survive).
  const RelaxationResult again = qp.Solve(p, p.var_lower, p.var_upper, kInfinity, Deadline());
  ASSERT_EQ(again.status, RelaxationStatus::kSolved);
  EXPECT_NEAR(again.objective, 0.5, 1e-6);
}

// Dives that fix binaries at random until the node is infeasible, each child started
// from its parent's active set: the dual method calls a node infeasible only when the
// interior point does too, never solves an infeasible one, and certifies most of them.
TEST(DualActiveSetQp, ChildrenCalledInfeasibleAreInfeasible) {
  int certified = 0, infeasible = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE(seed);
    const Miqp p = RandomSingularQp(45, 60, 100 + seed);
    const RelaxationResult root = Ipm(p, p.var_lower, p.var_upper);
    ASSERT_EQ(root.status, RelaxationStatus::kSolved);
    std::vector<int> token = DualActiveSetQp::ActiveSetAt(p, p.var_lower, p.var_upper, root);
    Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
    DualActiveSetQp qp;
    std::mt19937 rng(seed);
    for (int j = 2; j < p.num_variables(); j += 3) {
      lower(j) = upper(j) = static_cast<double>(rng() % 2);
      const RelaxationResult ipm = Ipm(p, lower, upper);
      const RelaxationResult dual = qp.SolveFrom(p, lower, upper, kInfinity, Deadline(), token);
      if (ipm.status == RelaxationStatus::kInfeasible) {
        EXPECT_NE(dual.status, RelaxationStatus::kSolved);
        ++infeasible;
        certified += dual.status == RelaxationStatus::kInfeasible;
        break;
      }
      ASSERT_EQ(ipm.status, RelaxationStatus::kSolved);
      EXPECT_NE(dual.status, RelaxationStatus::kInfeasible);
      if (dual.status != RelaxationStatus::kSolved) break;
      ExpectAgrees(p, dual, ipm);
      token = *dual.warm_token;
    }
  }
  EXPECT_GE(infeasible, 4);
  EXPECT_GE(certified, infeasible / 2);
}

TEST(DualActiveSetQp, ACutoffBelowTheOptimumEndsWithATrueFloor) {
  const Miqp p = RandomSingularQp(45, 40, 5);
  const RelaxationResult ipm = Ipm(p, p.var_lower, p.var_upper);
  ASSERT_EQ(ipm.status, RelaxationStatus::kSolved);
  const double cutoff = ipm.objective - 1e-3 * (1.0 + std::abs(ipm.objective));
  DualActiveSetQp qp;
  const RelaxationResult r = qp.Solve(p, p.var_lower, p.var_upper, cutoff, Deadline());
  ASSERT_EQ(r.status, RelaxationStatus::kCutoff);
  EXPECT_GE(r.objective, cutoff);
  EXPECT_LE(r.objective, ipm.objective + 1e-7 * (1.0 + std::abs(ipm.objective)));
}

Miqp TableIRoot(const std::string& course, int steps) {
  const Course c = LoadTableICourse(course, steps);
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  return formulation.miqp();
}

TEST(DualActiveSetQp, AgreesWithTheInteriorPointOnTableIRoots) {
  for (const char* course : {"hexapod_stepping_stones_45.yaml", "littledog_stepping_stones_45.yaml"}) {
    for (int steps : {12, 24}) {
      SCOPED_TRACE(std::string(course) + " " + std::to_string(steps));
      const Miqp p = TableIRoot(course, steps);
      DualActiveSetOptions options;  // every size and step count: agreement, not speed, is tested
      options.max_variables = 1500;
      options.max_warm_steps_per_variable = 1e3;
      DualActiveSetQp qp(options);
      const RelaxationResult dual = qp.Solve(p, p.var_lower, p.var_upper, kInfinity, Deadline());
      const RelaxationResult ipm = Ipm(p, p.var_lower, p.var_upper);
      ExpectAgrees(p, dual, ipm);
      const std::vector<int> seed = DualActiveSetQp::ActiveSetAt(p, p.var_lower, p.var_upper, ipm);
      DualActiveSetQp fresh(options);  // from the interior point's active set
      const RelaxationResult seeded = fresh.SolveFrom(p, p.var_lower, p.var_upper, kInfinity, Deadline(), seed);
      ExpectAgrees(p, seeded, ipm);
    }
  }
}

// A small branch-and-bound tree on a random QP, every node started from its parent's
// active set (the root's read off the interior point's answer), nodes taken in a random
// order (jumps between subtrees): each agrees with the interior point, and the starts from
// the parents take fewer steps in all than the same nodes started from nothing.
TEST(DualActiveSetQp, ChildrenStartedFromTheirParentsActiveSetMatchTheInteriorPoint) {
  const Miqp p = RandomSingularQp(60, 50, 7);
  struct Open {
    Eigen::VectorXd lower, upper;
    std::vector<int> parent_active;
  };
  const RelaxationResult root = Ipm(p, p.var_lower, p.var_upper);
  ASSERT_EQ(root.status, RelaxationStatus::kSolved);
  std::vector<Open> open{{p.var_lower, p.var_upper, DualActiveSetQp::ActiveSetAt(p, p.var_lower, p.var_upper, root)}};
  DualActiveSetQp qp, cold;
  std::mt19937 rng(5);
  int compared = 0;
  long warm_steps = 0, cold_steps = 0;
  while (!open.empty() && compared < 30) {
    const size_t pick = rng() % open.size();
    const Open node = open[pick];
    open.erase(open.begin() + static_cast<long>(pick));
    const RelaxationResult ipm = Ipm(p, node.lower, node.upper);
    const RelaxationResult dual = qp.SolveFrom(p, node.lower, node.upper, kInfinity, Deadline(), node.parent_active);
    if (ipm.status == RelaxationStatus::kInfeasible) {
      EXPECT_NE(dual.status, RelaxationStatus::kSolved);
      continue;
    }
    SCOPED_TRACE(compared);
    ExpectAgrees(p, dual, ipm);
    ASSERT_TRUE(dual.warm_token);
    const RelaxationResult from_nothing = cold.SolveFrom(p, node.lower, node.upper, kInfinity, Deadline(), {});
    ExpectAgrees(p, from_nothing, ipm);
    warm_steps += dual.iterations;
    cold_steps += from_nothing.iterations;
    ++compared;
    for (int j = 2; j < p.num_variables(); j += 3) {  // branch on the first fractional binary
      if (std::abs(dual.x(j) - std::round(dual.x(j))) < 1e-6) continue;
      for (double side : {0.0, 1.0}) {
        Open child{node.lower, node.upper, *dual.warm_token};
        child.lower(j) = child.upper(j) = side;
        open.push_back(child);
      }
      break;
    }
  }
  EXPECT_GE(compared, 10);
  EXPECT_LT(warm_steps, cold_steps);
}

// The same tree with the parent's point given, under each option it serves: the
// regularisation centred at the parent's point, the parent's moved active bounds entered
// as violated constraints, and both. Every node agrees with the interior point, its floor
// (the box certificate or the regularised one) stays below the interior point's optimum,
// and the floor is within 1e-4 of it. Children move bounds their parent's point was on
// (as bound propagation does), so that the entered bounds are exercised.
TEST(DualActiveSetQp, ChildrenStartedFromTheirParentsPointMatchTheInteriorPointUnderEachOption) {
  for (int variant = 1; variant < 4; ++variant) {
    SCOPED_TRACE(variant);
    DualActiveSetOptions options;
    options.proximal_centre = variant & 1;
    options.enter_moved_bounds = variant & 2;
    for (unsigned seed : {7u, 11u}) {
      const Miqp p = RandomSingularQp(60, 50, seed);
      struct Open {
        Eigen::VectorXd lower, upper, parent_x;
        std::vector<int> parent_active;
      };
      const RelaxationResult root = Ipm(p, p.var_lower, p.var_upper);
      ASSERT_EQ(root.status, RelaxationStatus::kSolved);
      std::vector<Open> open{
          {p.var_lower, p.var_upper, root.x, DualActiveSetQp::ActiveSetAt(p, p.var_lower, p.var_upper, root)}};
      DualActiveSetQp qp(options);
      std::mt19937 rng(seed);
      int compared = 0;
      while (!open.empty() && compared < 30) {
        const size_t pick = rng() % open.size();
        const Open node = open[pick];
        open.erase(open.begin() + static_cast<long>(pick));
        const RelaxationResult ipm = Ipm(p, node.lower, node.upper);
        const RelaxationResult dual =
            qp.SolveFrom(p, node.lower, node.upper, kInfinity, Deadline(), node.parent_active, &node.parent_x);
        if (ipm.status == RelaxationStatus::kInfeasible) {
          EXPECT_NE(dual.status, RelaxationStatus::kSolved);
          continue;
        }
        SCOPED_TRACE(compared);
        ExpectAgrees(p, dual, ipm);
        ASSERT_TRUE(dual.warm_token);
        ++compared;
        for (int j = 2; j < p.num_variables(); j += 3) {
          if (std::abs(dual.x(j) - std::round(dual.x(j))) < 1e-6) continue;
          for (double side : {0.0, 1.0}) {
            Open child{node.lower, node.upper, dual.x, *dual.warm_token};
            child.lower(j) = child.upper(j) = side;
            // Propagated bounds: two bounds the parent's point was on moved past it.
            int moved = 0;
            for (int step = 0, k = static_cast<int>(rng() % 60); step < 60 && moved < 2; ++step, k = (k + 7) % 60) {
              if (k == j || child.upper(k) - child.lower(k) < 0.2) continue;
              if (dual.x(k) - child.lower(k) < 1e-9) {
                child.lower(k) += 0.05;
              } else if (child.upper(k) - dual.x(k) < 1e-9) {
                child.upper(k) -= 0.05;
              } else {
                continue;
              }
              ++moved;
            }
            open.push_back(child);
          }
          break;
        }
      }
      EXPECT_GE(compared, 10);
    }
  }
}

// The planner's node relaxations through the factory: the root (no token) is the
// interior point's answer and hands its active set on; a child given it agrees with the
// interior point, through the factory and by the dual method alone.
TEST(DualActiveSetQp, TheFactorysDualSolverStartsTableIChildrenFromTheRootsActiveSet) {
  for (const char* course : {"hexapod_stepping_stones_45.yaml", "littledog_stepping_stones_45.yaml"}) {
    SCOPED_TRACE(course);
    const Miqp p = TableIRoot(course, 12);
    auto solver = MakeRelaxationSolver(RelaxationBackend::kDualActiveSetWithFallbacks);
    RelaxationRequest request;
    const RelaxationResult root = solver->Solve(p, request);
    ASSERT_EQ(root.status, RelaxationStatus::kSolved);
    ASSERT_TRUE(root.warm_token);
    int children = 0;
    for (int j = 0; j < p.num_variables() && children < 4; ++j) {
      if (!p.is_integer[j] || std::abs(root.x(j) - std::round(root.x(j))) < 1e-3) continue;
      for (double side : {0.0, 1.0}) {
        RelaxationRequest child;
        child.lower = p.var_lower;
        child.upper = p.var_upper;
        child.lower(j) = child.upper(j) = side;
        child.warm_token = root.warm_token;
        const RelaxationResult ipm = Ipm(p, child.lower, child.upper);
        const RelaxationResult dual = solver->Solve(p, child);
        if (ipm.status == RelaxationStatus::kInfeasible) {
          EXPECT_EQ(dual.status, RelaxationStatus::kInfeasible);
          continue;
        }
        ExpectAgrees(p, dual, ipm);
        EXPECT_TRUE(dual.warm_token);
        DualActiveSetQp qp;  // the dual method alone, from the root's active set
        ExpectAgrees(p, qp.SolveFrom(p, child.lower, child.upper, kInfinity, Deadline(), *root.warm_token), ipm);
        ++children;
      }
    }
    EXPECT_GE(children, 2);
  }
}

}  // namespace
}  // namespace mfp
