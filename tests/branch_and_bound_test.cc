// Branch-and-bound on a catalogue of small MIQPs whose optima are worked out by hand in
// the comments; every search strategy must prove each of them.
#include "planner/search/branch_and_bound.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include "planner/miqp/miqp_builder.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/qp/internal/ipopt_relaxation_solver.h"

namespace mfp {
namespace {

struct CatalogueEntry {
  std::string name;
  Miqp problem;
  SolveStatus status;
  double objective;        // hand-computed optimum
  Eigen::VectorXd x;       // hand-computed optimal point (integer entries at least)
};

// min (x - 0.6)^2, x binary. x = 0 gives 0.36, x = 1 gives 0.16: optimum x = 1, 0.16.
CatalogueEntry OneBinary() {
  MiqpBuilder b;
  const int x = b.AddBinary("x");
  b.AddSquaredCost(LinExpr::Var(x) - LinExpr::Constant(0.6), 1.0);
  return {"one_binary", b.Build(), SolveStatus::kOptimal, 0.16, Eigen::VectorXd::Constant(1, 1.0)};
}

// Knapsack: max 5a + 4b + 3c s.t. 2a + 3b + c <= 5, binaries. Subsets within the
// capacity: {a,b} weight 5 value 9, {a,c} 3 -> 8, {b,c} 4 -> 7, singles <= 5; {a,b,c}
// weighs 6. Optimum -9 at (1, 1, 0). The LP relaxation is fractional (c = 1, a = 1,
// b = 2/3, value 10.67), so branching is needed.
CatalogueEntry Knapsack() {
  MiqpBuilder b;
  const int a = b.AddBinary("a"), bb = b.AddBinary("b"), c = b.AddBinary("c");
  b.AddRow("capacity", LinExpr::Var(a, 2) + LinExpr::Var(bb, 3) + LinExpr::Var(c, 1), -kInfinity, 5);
  b.AddLinearCost(LinExpr::Var(a, -5) + LinExpr::Var(bb, -4) + LinExpr::Var(c, -3));
  Eigen::VectorXd x(3);
  x << 1, 1, 0;
  return {"knapsack", b.Build(), SolveStatus::kOptimal, -9.0, x};
}

// y in [0, 4] in one of the intervals [lo_k, hi_k], chosen by a one-of group of
// binaries h_k with big-M rows (M = 4); minimise (y - 2.5)^2 + sum_k linear_k h_k.
Miqp Intervals(const std::vector<double>& lo, const std::vector<double>& hi, const std::vector<double>& linear) {
  MiqpBuilder b;
  const int y = b.AddVariable("y", 0.0, 4.0, false);
  LinExpr one;
  std::vector<int> group;
  for (size_t k = 0; k < lo.size(); ++k) {
    const int h = b.AddBinary("h" + std::to_string(k));
    group.push_back(h);
    one += LinExpr::Var(h);
    const double M = 4.0;
    // y >= lo - M (1 - h)  and  y <= hi + M (1 - h)
    b.AddRow("lo" + std::to_string(k), LinExpr::Var(y) - LinExpr::Var(h, M), lo[k] - M, kInfinity);
    b.AddRow("hi" + std::to_string(k), LinExpr::Var(y) + LinExpr::Var(h, M), -kInfinity, hi[k] + M);
    if (linear[k] != 0.0) b.AddLinearCost(LinExpr::Var(h, linear[k]));
  }
  b.AddRow("one", one, 1, 1);
  b.AddSos1Group(group);
  b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(2.5), 1.0);
  return b.Build();
}

// One of three intervals for y: [0, 1], [2, 2.2] or [3, 4]. Distances to 2.5: 1.5, 0.3,
// 0.5, so the optimum picks the middle interval with y = 2.2 and cost 0.09.
CatalogueEntry IntervalChoice() {
  Eigen::VectorXd x(4);
  x << 2.2, 0, 1, 0;
  return {"interval_choice", Intervals({0, 2, 3}, {1, 2.2, 4}, {0, 0, 0}), SolveStatus::kOptimal, 0.09, x};
}

// x + y = 1.5 with x, y binary has no solution (sums are 0, 1 or 2).
CatalogueEntry Infeasible() {
  MiqpBuilder b;
  const int x = b.AddBinary("x"), y = b.AddBinary("y");
  b.AddRow("sum", LinExpr::Var(x) + LinExpr::Var(y), 1.5, 1.5);
  b.AddLinearCost(LinExpr::Var(x));
  return {"infeasible", b.Build(), SolveStatus::kInfeasible, kInfinity, Eigen::VectorXd()};
}

// A general integer: min (z - 2.4)^2, z in {0..5}: z = 2 gives 0.16, z = 3 gives 0.36.
CatalogueEntry GeneralInteger() {
  MiqpBuilder b;
  const int z = b.AddVariable("z", 0.0, 5.0, true);
  b.AddSquaredCost(LinExpr::Var(z) - LinExpr::Constant(2.4), 1.0);
  return {"general_integer", b.Build(), SolveStatus::kOptimal, 0.16, Eigen::VectorXd::Constant(1, 2.0)};
}

// Coupled binaries: min (x1 + x2 - 1.2)^2 + 0.1 x1. (0,0): 1.44, (1,0): 0.04 + 0.1 = 0.14,
// (0,1): 0.04, (1,1): 0.64 + 0.1 = 0.74. Optimum (0, 1) with 0.04.
CatalogueEntry CoupledBinaries() {
  MiqpBuilder b;
  const int x1 = b.AddBinary("x1"), x2 = b.AddBinary("x2");
  b.AddSquaredCost(LinExpr::Var(x1) + LinExpr::Var(x2) - LinExpr::Constant(1.2), 1.0);
  b.AddLinearCost(LinExpr::Var(x1, 0.1));
  Eigen::VectorXd x(2);
  x << 0, 1;
  return {"coupled_binaries", b.Build(), SolveStatus::kOptimal, 0.04, x};
}

// Mixed: continuous u in [-1, 3] and binary s; min (u - 2)^2 + 3 s subject to u <= 1 + 2 s.
// s = 0: u = 1, cost 1. s = 1: u = 2, cost 3. Optimum s = 0, u = 1, cost 1.
CatalogueEntry Mixed() {
  MiqpBuilder b;
  const int u = b.AddVariable("u", -1.0, 3.0, false);
  const int s = b.AddBinary("s");
  b.AddRow("cap", LinExpr::Var(u) - LinExpr::Var(s, 2.0), -kInfinity, 1.0);
  b.AddSquaredCost(LinExpr::Var(u) - LinExpr::Constant(2.0), 1.0);
  b.AddLinearCost(LinExpr::Var(s, 3.0));
  Eigen::VectorXd x(2);
  x << 1, 0;
  return {"mixed", b.Build(), SolveStatus::kOptimal, 1.0, x};
}

// Two intervals for y, [3, 4] (h_a) and [2, 2.2] (h_b), with a cost of -0.01 on h_a.
// The relaxation keeps y = 2.5 and pushes h_a to its largest value 0.875, so rounding it
// picks h_a: y = 3, cost 0.24. The optimum is h_b = 1, y = 2.2, cost 0.09.
Miqp DecoyInterval() { return Intervals({3, 2}, {4, 2.2}, {-0.01, 0}); }

// Solves problem with the default options as changed by `set`, relaxations by Ipopt or
// the interior-point QP.
BranchAndBoundResult SolveWith(const Miqp& problem, bool ipopt,
                               const std::function<void(BranchAndBoundOptions*)>& set) {
  const auto solver = ipopt ? MakeIpoptRelaxationSolver() : MakeInteriorPointRelaxationSolver();
  BranchAndBoundOptions options;
  set(&options);
  return SolveBranchAndBound(problem, *solver, options);
}

// The gap the catalogue's searches are asked to prove: what the interior point's floors
// certify on these small QPs (accepted at a coarse dual residual, a floor can lie up to
// about 1e-3 below its objective), not the digits of the optimum, which are checked apart.
constexpr double kProofGap = 1e-3;

std::vector<CatalogueEntry> Catalogue() {
  return {OneBinary(), Knapsack(), IntervalChoice(), Infeasible(), GeneralInteger(), CoupledBinaries(), Mixed()};
}

struct Strategy {
  NodeSelection selection;
  BranchingRule branching;
  bool rounding;
  bool ipopt;  // relaxations by Ipopt, else by mfp's interior-point method
};

class BranchAndBoundCatalogue : public ::testing::TestWithParam<Strategy> {};

TEST_P(BranchAndBoundCatalogue, ProvesEveryHandComputedOptimum) {
  const auto solver = GetParam().ipopt ? MakeIpoptRelaxationSolver() : MakeInteriorPointRelaxationSolver();
  BranchAndBoundOptions options;
  options.node_selection = GetParam().selection;
  options.branching = GetParam().branching;
  options.rounding_heuristic = GetParam().rounding;
  options.relative_gap = kProofGap;
  options.absolute_gap = kProofGap;
  for (const CatalogueEntry& entry : Catalogue()) {
    SCOPED_TRACE(entry.name);
    const BranchAndBoundResult r = SolveBranchAndBound(entry.problem, *solver, options);
    ASSERT_EQ(ToString(r.status), ToString(entry.status));
    if (entry.status != SolveStatus::kOptimal) continue;
    EXPECT_NEAR(r.objective, entry.objective, 1e-6);
    EXPECT_LE(r.bound, entry.objective + 1e-6);
    EXPECT_LE(r.gap, kProofGap);
    ASSERT_EQ(r.x.size(), entry.x.size());
    for (int j = 0; j < r.x.size(); ++j) EXPECT_NEAR(r.x(j), entry.x(j), 1e-5) << "variable " << j;
    EXPECT_GE(r.relaxations, 1);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Strategies, BranchAndBoundCatalogue,
    ::testing::Values(Strategy{NodeSelection::kBestBound, BranchingRule::kMostFractional, false, true},
                      Strategy{NodeSelection::kDepthFirst, BranchingRule::kMostFractional, true, true},
                      Strategy{NodeSelection::kDiveThenBestBound, BranchingRule::kSos1Split, true, true},
                      Strategy{NodeSelection::kDiveThenBestBound, BranchingRule::kSos1Split, false, true},
                      Strategy{NodeSelection::kBestBound, BranchingRule::kMostFractional, false, false},
                      Strategy{NodeSelection::kDepthFirst, BranchingRule::kMostFractional, true, false},
                      Strategy{NodeSelection::kDiveThenBestBound, BranchingRule::kSos1Split, true, false},
                      Strategy{NodeSelection::kBestBound, BranchingRule::kReliability, false, false},
                      Strategy{NodeSelection::kDiveThenBestBound, BranchingRule::kReliability, true, false},
                      Strategy{NodeSelection::kBestBoundWithPlunging, BranchingRule::kGroupOrder, false, false},
                      Strategy{NodeSelection::kBestBoundWithPlunging, BranchingRule::kReliability, true, true}));

TEST(BranchAndBound, TwoWorkersProveEveryHandComputedOptimum) {
  // Node relaxations, roundings and strong-branching trials two at a time, on two IPM
  // solvers and on two Ipopt solvers (which take turns on Ipopt's global state).
  for (const bool ipopt : {false, true}) {
    std::unique_ptr<RelaxationSolver> a = ipopt ? MakeIpoptRelaxationSolver() : MakeInteriorPointRelaxationSolver();
    std::unique_ptr<RelaxationSolver> b = ipopt ? MakeIpoptRelaxationSolver() : MakeInteriorPointRelaxationSolver();
    const std::vector<RelaxationSolver*> workers = {a.get(), b.get()};
    for (const BranchingRule rule : {BranchingRule::kGroupOrder, BranchingRule::kReliability}) {
      BranchAndBoundOptions options;
      options.branching = rule;
      options.relative_gap = kProofGap;
      options.absolute_gap = kProofGap;
      for (const CatalogueEntry& entry : Catalogue()) {
        SCOPED_TRACE(entry.name + (ipopt ? " ipopt" : " ipm"));
        const BranchAndBoundResult r = SolveBranchAndBound(entry.problem, workers, options);
        ASSERT_EQ(ToString(r.status), ToString(entry.status));
        if (entry.status != SolveStatus::kOptimal) continue;
        EXPECT_NEAR(r.objective, entry.objective, 1e-6);
        EXPECT_LE(r.bound, entry.objective + 1e-6);
        EXPECT_GE(r.bound, entry.objective - kProofGap);
        for (int j = 0; j < r.x.size(); ++j) EXPECT_NEAR(r.x(j), entry.x(j), 1e-5) << "variable " << j;
      }
    }
  }
}

TEST(BranchAndBound, ReportsEachBetterIncumbentWithAValidBound) {
  // Depth first without rounding on the decoy: first the decoy leaf (0.24), then the
  // optimum (0.09). Each report improves on the last and its bound stays at or below
  // the optimum; the last one is the result.
  const auto solver = MakeInteriorPointRelaxationSolver();
  BranchAndBoundOptions options;
  options.node_selection = NodeSelection::kDepthFirst;
  options.rounding_heuristic = false;
  std::vector<BranchAndBoundResult> reports;
  options.on_incumbent = [&reports](const BranchAndBoundResult& r) { reports.push_back(r); };
  const BranchAndBoundResult r = SolveBranchAndBound(DecoyInterval(), *solver, options);
  ASSERT_EQ(r.status, SolveStatus::kOptimal);
  ASSERT_FALSE(reports.empty());
  for (size_t k = 0; k < reports.size(); ++k) {
    EXPECT_LE(reports[k].bound, 0.09 + 1e-6);
    EXPECT_LE(reports[k].bound, reports[k].objective);
    EXPECT_GE(reports[k].nodes, 1);
    if (k > 0) {
      EXPECT_LT(reports[k].objective, reports[k - 1].objective);
    }
  }
  EXPECT_NEAR(reports.back().objective, r.objective, 1e-12);
}

TEST(BranchAndBound, KnapsackNeedsBranching) {
  // Without rounding, the fractional root forces at least three nodes (root + 2 children).
  const BranchAndBoundResult r =
      SolveWith(Knapsack().problem, true, [](BranchAndBoundOptions* o) { o->rounding_heuristic = false; });
  EXPECT_EQ(r.status, SolveStatus::kOptimal);
  EXPECT_GE(r.nodes, 3);
}

TEST(BranchAndBound, NodeLimitReturnsBestSoFarWithItsGap) {
  // One node only. The interval choice's root relaxation reaches y = 2.5 (cost 0) with
  // fractional choices; rounding picks one interval, whose fixed QP costs at least 0.09.
  // The result must say unproven (feasible), keep the root bound 0 and report the gap.
  const BranchAndBoundResult r =
      SolveWith(IntervalChoice().problem, true, [](BranchAndBoundOptions* o) { o->max_nodes = 1; });
  ASSERT_EQ(r.status, SolveStatus::kFeasible);
  EXPECT_NEAR(r.bound, 0.0, 1e-6);
  EXPECT_GE(r.objective, 0.09 - 1e-6);
  EXPECT_NEAR(r.gap, r.objective, 1e-6);  // (objective - 0) / max(1, objective)
}

TEST(BranchAndBound, GapTolerancePrunesButKeepsTheBoundValid) {
  // With a 0.3 absolute gap the root's rounding (0.24) ends the search: the root's
  // bound (about 0) cannot beat it by more than 0.3. The bound reported must be the
  // root's, not the incumbent's: at or below the true optimum 0.09.
  const BranchAndBoundResult r = SolveWith(DecoyInterval(), false, [](BranchAndBoundOptions* o) {
    o->relative_gap = 0.0;
    o->absolute_gap = 0.3;
  });
  ASSERT_EQ(r.status, SolveStatus::kOptimal);
  EXPECT_NEAR(r.objective, 0.24, 1e-6);  // the decoy: the search did stop early
  EXPECT_LE(r.bound, 0.09 + 1e-6);
  EXPECT_NEAR(r.gap, (r.objective - r.bound) / std::max(1.0, std::abs(r.objective)), 1e-12);
}

TEST(BranchAndBound, StrongBranchingCountsItsSolvesAsRelaxations) {
  // Knapsack without rounding must branch; reliability branching strong-branches the
  // fractional root, so some relaxations are trials, and the optimum is still proven.
  const BranchAndBoundResult r = SolveWith(Knapsack().problem, false, [](BranchAndBoundOptions* o) {
    o->rounding_heuristic = false;
    o->branching = BranchingRule::kReliability;
  });
  EXPECT_EQ(r.status, SolveStatus::kOptimal);
  EXPECT_NEAR(r.objective, -9.0, 1e-6);
  EXPECT_GE(r.strong_branching_solves, 2);
  EXPECT_GE(r.relaxations, r.nodes + r.strong_branching_solves - r.propagation_prunes);
}

// Proves the catalogue with a search feature off and on (`enable`): the same optima and
// bounds either way. Returns how often the feature acted (`acted`, summed over the runs
// with it on); with it off it must not act at all.
int CatalogueWithAndWithout(const std::function<void(BranchAndBoundOptions*, bool)>& enable,
                            const std::function<int(const BranchAndBoundResult&)>& acted) {
  const auto solver = MakeInteriorPointRelaxationSolver();
  int total = 0;
  for (const CatalogueEntry& entry : Catalogue()) {
    SCOPED_TRACE(entry.name);
    BranchAndBoundResult r[2];
    for (int on = 0; on < 2; ++on) {
      BranchAndBoundOptions options;
      options.relative_gap = kProofGap;
      options.absolute_gap = kProofGap;
      enable(&options, on == 1);
      r[on] = SolveBranchAndBound(entry.problem, *solver, options);
    }
    EXPECT_EQ(acted(r[0]), 0);
    total += acted(r[1]);
    EXPECT_EQ(ToString(r[1].status), ToString(entry.status));
    if (entry.status != SolveStatus::kOptimal) continue;
    EXPECT_NEAR(r[1].objective, entry.objective, 1e-6);
    EXPECT_LE(r[1].bound, entry.objective + 1e-6);
    EXPECT_GE(r[1].bound, entry.objective - kProofGap);
  }
  return total;
}

TEST(BranchAndBound, ReducedCostFixingKeepsEveryOptimum) {
  // The certificate must rule values out somewhere, else this test would prove nothing.
  EXPECT_GE(CatalogueWithAndWithout([](BranchAndBoundOptions* o, bool on) { o->reduced_cost_fixing = on; },
                                    [](const BranchAndBoundResult& r) { return r.reduced_cost_fixings; }),
            1);
}

TEST(BranchAndBound, EarlyCutoffKeepsEveryOptimum) {
  // Node solves stopped as soon as they cannot beat the incumbent; some must stop early.
  EXPECT_GE(CatalogueWithAndWithout([](BranchAndBoundOptions* o, bool on) { o->early_cutoff = on; },
                                    [](const BranchAndBoundResult& r) { return r.early_cutoffs; }),
            1);
}

TEST(BranchAndBound, GroupProbingKeepsEveryOptimum) {
  // Every node, every second level, and under a work cap; the catalogue's one-of group
  // (interval_choice) must be probed somewhere.
  for (const int interval : {1, 2}) {
    for (const double work : {0.0, 0.5}) {
      SCOPED_TRACE(interval);
      SCOPED_TRACE(work);
      EXPECT_GE(CatalogueWithAndWithout(
                    [&](BranchAndBoundOptions* o, bool on) {
                      o->group_probing = on;
                      o->group_probing_interval = interval;
                      o->group_probing_work = work;
                    },
                    [](const BranchAndBoundResult& r) { return r.probed_nodes; }),
                1);
    }
  }
}

// Two feet x, y in [0, 10] with x + y <= 10 and a one-of choice: z1 = 1 asks x >= 6 and
// y >= 6 (impossible together, which propagation of single rows does not see and probing
// does), z2 = 1 costs 10. The relaxation takes z1 = 5/6: both integers fractional. Probing
// after the root's relaxation fixes z1 = 0 and z2 = 1, so no variable is left to branch on
// in the probed box: the root must be solved again there, not rounded and dropped.
Miqp ProbingFixesEveryFractionalInteger() {
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0.0, 10.0, false);
  const int y = b.AddVariable("y", 0.0, 10.0, false);
  const int z1 = b.AddBinary("z1");
  const int z2 = b.AddBinary("z2");
  b.AddRow("x_if_z1", LinExpr::Var(x) + LinExpr::Var(z1, -6.0), 0.0, kInfinity);
  b.AddRow("y_if_z1", LinExpr::Var(y) + LinExpr::Var(z1, -6.0), 0.0, kInfinity);
  b.AddRow("room", LinExpr::Var(x) + LinExpr::Var(y), -kInfinity, 10.0);
  b.AddRow("one_of", LinExpr::Var(z1) + LinExpr::Var(z2), 1.0, 1.0);
  b.AddSos1Group({z1, z2});
  b.AddLinearCost(LinExpr::Var(z2, 10.0));
  b.AddSquaredCost(LinExpr::Var(x) + LinExpr::Var(y) + LinExpr::Constant(-1.0), 0.01);
  return b.Build();
}

TEST(BranchAndBound, ARootWhoseProbingFixesEveryFractionalIntegerIsSolvedAgain) {
  for (const bool probing : {false, true}) {
    SCOPED_TRACE(probing);
    const BranchAndBoundResult r =
        SolveWith(ProbingFixesEveryFractionalInteger(), false, [&](BranchAndBoundOptions* o) {
          o->group_probing = probing;
          o->rounding_heuristic = false;  // no plan but the search's own
          o->group_probing_work = 0.0;
        });
    ASSERT_EQ(r.status, SolveStatus::kOptimal) << ToString(r.status);
    ASSERT_EQ(r.x.size(), 4);
    EXPECT_NEAR(r.x(3), 1.0, 1e-6);                     // z2
    EXPECT_NEAR(r.objective, 10.0, 1e-4);               // z2's cost; x + y = 1 costs nothing
    EXPECT_LE(r.bound, r.objective + 1e-9);
  }
}

TEST(BranchAndBound, RinsKeepsEveryOptimum) {
  EXPECT_GE(CatalogueWithAndWithout(
                [](BranchAndBoundOptions* o, bool on) {
                  o->rins_frequency = on ? 1 : 0;
                  o->rins_after_nodes = 0;  // at the root and every node, whatever the gap
                  o->rins_backoff = 1.0;
                  o->rins_min_gap = 0.0;
                  o->rins_min_fixed_fraction = 0.0;
                  o->rins_agreement = 0.5;
                },
                [](const BranchAndBoundResult& r) { return r.rins_runs; }),
            1);
}

TEST(BranchAndBound, RinsFromTheRootImprovesTheRoundingsDecoy) {
  // DecoyInterval: the root's rounding picks h_a (cost 0.24); RINS at the root (where
  // nothing is fixed with min fraction 0) searches the rest and finds the optimum 0.09
  // within its own node cap, before the main search's first branching.
  BranchAndBoundOptions options;
  options.rins_frequency = 1000;
  options.rins_after_nodes = 0;  // at the root
  options.rins_min_gap = 0.0;
  options.rins_min_fixed_fraction = 0.0;
  options.max_nodes = 1;
  const auto solver = MakeInteriorPointRelaxationSolver();
  BranchAndBoundOptions off = options;
  off.rins_frequency = 0;
  const BranchAndBoundResult without = SolveBranchAndBound(DecoyInterval(), *solver, off);
  EXPECT_NEAR(without.objective, 0.24, 1e-5);
  const BranchAndBoundResult with = SolveBranchAndBound(DecoyInterval(), *solver, options);
  EXPECT_EQ(with.rins_runs, 1);
  EXPECT_EQ(with.rins_improvements, 1);
  EXPECT_NEAR(with.objective, 0.09, 1e-5);
  EXPECT_EQ(with.nodes, 1);
}

TEST(BranchAndBound, TimeLimitWithoutIncumbentSaysSo) {
  const BranchAndBoundResult r =
      SolveWith(Knapsack().problem, true, [](BranchAndBoundOptions* o) { o->time_limit_s = 0.0; });
  EXPECT_EQ(r.status, SolveStatus::kNoSolution);
  EXPECT_EQ(r.x.size(), 0);
}

TEST(BranchAndBound, AnytimeSearchRunsPastItsTimeLimitToItsFirstIncumbent) {
  // time_limit_needs_incumbent: the time limit alone (0 s) does not end a search that
  // has no plan yet; it goes on to its first incumbent, then stops (the caller's
  // deadline, 60 s here, is far off). Without the flag the same search has none.
  const auto solver = MakeIpoptRelaxationSolver();
  BranchAndBoundOptions options;
  options.time_limit_s = 0.0;
  options.time_limit_needs_incumbent = true;
  options.deadline = Deadline::After(60.0);
  options.rounding_heuristic = false;  // the incumbent must come from the tree
  const BranchAndBoundResult r = SolveBranchAndBound(Knapsack().problem, *solver, options);
  EXPECT_TRUE(HasPlan(r.status)) << ToString(r.status);
  ASSERT_EQ(r.x.size(), Knapsack().problem.num_variables());
  EXPECT_LE(Knapsack().problem.MaxViolation(r.x), 1e-6);
  EXPECT_LE(r.bound, r.objective);
  // An expired caller's deadline still ends it, plan or not.
  options.deadline = Deadline::After(0.0);
  EXPECT_EQ(SolveBranchAndBound(Knapsack().problem, *solver, options).status, SolveStatus::kNoSolution);
}

TEST(BranchAndBound, ExtraRoundingProposalsAreUsed) {
  // A proposal of the optimum itself makes the root's incumbent optimal at once.
  const auto solver = MakeIpoptRelaxationSolver();
  BranchAndBoundOptions options;
  options.max_nodes = 1;
  int calls = 0;
  const RoundingHeuristic propose = [&calls](const Eigen::VectorXd& relaxed) {
    ++calls;
    Eigen::VectorXd x = relaxed;
    x << 1, 1, 0;
    return std::vector<Eigen::VectorXd>{x};
  };
  const BranchAndBoundResult r = SolveBranchAndBound(Knapsack().problem, *solver, options, propose);
  EXPECT_GE(calls, 1);
  EXPECT_NEAR(r.objective, -9.0, 1e-6);
}

// Root-only searches of the knapsack whose rounding proposes `proposals` (then the
// search's own simple rounding).
BranchAndBoundResult RootWithProposals(const std::vector<Eigen::VectorXd>& proposals, bool propagation,
                                       bool stop_at_first_plan) {
  const auto solver = MakeIpoptRelaxationSolver();
  BranchAndBoundOptions options;
  options.max_nodes = 1;
  options.bound_propagation = propagation;
  options.rounding_stops_at_first_plan = stop_at_first_plan;
  const RoundingHeuristic propose = [&proposals](const Eigen::VectorXd&) { return proposals; };
  return SolveBranchAndBound(Knapsack().problem, *solver, options, propose);
}

Eigen::VectorXd Choice(double a, double b, double c) {
  Eigen::VectorXd x(3);
  x << a, b, c;
  return x;
}

TEST(BranchAndBound, AProposalThatPropagationRulesOutGetsNoQp) {
  // {a, b, c} weighs 6 > 5: propagation over the capacity row proves that no point
  // completes it, so it costs no QP; {a, b} is the optimum either way.
  const std::vector<Eigen::VectorXd> proposals = {Choice(1, 1, 1), Choice(1, 1, 0)};
  const BranchAndBoundResult with = RootWithProposals(proposals, true, false);
  const BranchAndBoundResult without = RootWithProposals(proposals, false, false);
  EXPECT_NEAR(with.objective, -9.0, 1e-6);
  EXPECT_NEAR(without.objective, -9.0, 1e-6);
  EXPECT_LE(with.relaxations + 1, without.relaxations);
}

TEST(BranchAndBound, RoundingsCanStopAtTheFirstPlan) {
  // Both proposals are plans as they are ({a, c}: -8, {a, b}: -9), so the search holds
  // the optimum before any rounding QP: stopping at the first plan solves none of them
  // (the root's relaxation only); completing every proposal solves one each.
  const std::vector<Eigen::VectorXd> proposals = {Choice(1, 0, 1), Choice(1, 1, 0)};
  const BranchAndBoundResult first = RootWithProposals(proposals, true, true);
  const BranchAndBoundResult all = RootWithProposals(proposals, true, false);
  EXPECT_NEAR(first.objective, -9.0, 1e-6);
  EXPECT_NEAR(all.objective, -9.0, 1e-6);
  EXPECT_EQ(first.relaxations, 1);
  EXPECT_GE(all.relaxations, 3);
}

// An interior-point solver that records the status of each solve whose request has
// every integer of Intervals fixed (the completions of roundings).
class CompletionRecorder : public RelaxationSolver {
 public:
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    RelaxationResult r = inner_->Solve(problem, request);
    bool all_fixed = request.lower.size() > 0;
    for (int j = 0; all_fixed && j < problem.num_variables(); ++j) {
      if (problem.is_integer[j]) all_fixed = request.lower(j) == request.upper(j);
    }
    if (all_fixed) completions.push_back(r.status);
    return r;
  }
  std::string Name() const override { return "completion recorder"; }
  std::vector<RelaxationStatus> completions;

 private:
  std::unique_ptr<RelaxationSolver> inner_ = MakeInteriorPointRelaxationSolver();
};

TEST(BranchAndBound, ARoundingCompletionThatCannotBeatTheIncumbentStopsAtTheCutoff) {
  // IntervalChoice: the first proposal, the middle interval at y = 2.2, is a plan as it
  // is (0.09); the second, the first interval, completes to y = 1 at cost 2.25. Its QP
  // may stop as soon as it proves that it cannot end below 0.09; the middle interval's
  // own completion ends at 0.09 itself and is solved to the end.
  CompletionRecorder solver;
  BranchAndBoundOptions options;
  options.max_nodes = 1;
  Eigen::VectorXd middle(4), first(4);
  middle << 2.2, 0, 1, 0;
  first << 2.2, 1, 0, 0;
  const RoundingHeuristic propose = [&](const Eigen::VectorXd&) { return std::vector<Eigen::VectorXd>{middle, first}; };
  const BranchAndBoundResult r = SolveBranchAndBound(IntervalChoice().problem, solver, options, propose);
  EXPECT_NEAR(r.objective, 0.09, 1e-6);
  ASSERT_GE(solver.completions.size(), 2u);
  EXPECT_EQ(solver.completions[0], RelaxationStatus::kSolved);
  EXPECT_EQ(solver.completions[1], RelaxationStatus::kCutoff);
}

TEST(BranchAndBound, AStalledSearchEndsWithItsIncumbent) {
  // The root's proposal {a, c} (value -8) is not optimal; the search finds -9 by
  // branching. With a stall limit shorter than any node, the search ends right after the
  // root with the proposal, as at its time limit; without it, it proves -9. (The root's
  // own rounding, (1, 1, 1), weighs 6: infeasible.)
  const auto solver = MakeIpoptRelaxationSolver();
  BranchAndBoundOptions options;
  const RoundingHeuristic propose = [](const Eigen::VectorXd& relaxed) {
    Eigen::VectorXd x = relaxed;
    x << 1, 0, 1;
    return std::vector<Eigen::VectorXd>{x};
  };
  const BranchAndBoundResult full = SolveBranchAndBound(Knapsack().problem, *solver, options, propose);
  EXPECT_EQ(full.status, SolveStatus::kOptimal);
  EXPECT_NEAR(full.objective, -9.0, 1e-6);
  EXPECT_GE(full.nodes, 3);
  options.stall_time_fraction = 1e-12;  // of time_limit_s (10 s): 10 ps
  const BranchAndBoundResult stalled = SolveBranchAndBound(Knapsack().problem, *solver, options, propose);
  EXPECT_EQ(stalled.status, SolveStatus::kTimeLimit);
  EXPECT_NEAR(stalled.objective, -8.0, 1e-6);
  EXPECT_EQ(stalled.nodes, 1);
  EXPECT_LE(stalled.bound, -8.0);
}

// min (x - 1)^2 with x <= 1 + a, x <= 1 + b, a + b = 1 (binaries): x = 1 whatever the
// choice, so the relaxation's (a, b) = (0.5, 0.5) (the interior point's centre) is
// fractional only in appearance: (1, 0) is just as good.
Miqp ChoiceThatDoesNotMatter() {
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 3, false), a = b.AddBinary("a"), c = b.AddBinary("b");
  b.AddRow("cap_a", LinExpr::Var(x) - LinExpr::Var(a), -kInfinity, 1.0);
  b.AddRow("cap_b", LinExpr::Var(x) - LinExpr::Var(c), -kInfinity, 1.0);
  b.AddRow("one", LinExpr::Var(a) + LinExpr::Var(c), 1.0, 1.0);
  b.AddSquaredCost(LinExpr::Var(x) - LinExpr::Constant(1.0), 1.0);
  return b.Build();
}

// Sets ChoiceThatDoesNotMatter's point (x, a, b).
void SetChoicePoint(Eigen::VectorXd* point, double x, double a, double b) {
  (*point)(0) = x;
  (*point)(1) = a;
  (*point)(2) = b;
}

TEST(BranchAndBound, AnEquivalentPointWithIntegralChoicesEndsTheNode) {
  const Miqp p = ChoiceThatDoesNotMatter();
  const auto solver = MakeInteriorPointRelaxationSolver();
  BranchAndBoundOptions options;
  options.rounding_heuristic = false;
  options.absolute_gap = kProofGap;  // the optimum is 0: the default 1e-6 is below what the floors certify
  const BranchAndBoundResult plain = SolveBranchAndBound(p, *solver, options);
  ASSERT_EQ(plain.status, SolveStatus::kOptimal);
  EXPECT_GE(plain.nodes, 2);  // the root branches on a or b
  EXPECT_EQ(plain.equivalent_points, 0);

  options.equivalent_point = [](const Eigen::VectorXd& lower, const Eigen::VectorXd&, Eigen::VectorXd* x) {
    if (lower(2) > 0.5) return false;  // b fixed to 1: not this choice
    SetChoicePoint(x, (*x)(0), 1.0, 0.0);
    return true;
  };
  const BranchAndBoundResult snapped = SolveBranchAndBound(p, *solver, options);
  ASSERT_EQ(snapped.status, SolveStatus::kOptimal);
  EXPECT_EQ(snapped.nodes, 1);
  EXPECT_EQ(snapped.equivalent_points, 1);
  EXPECT_NEAR(snapped.objective, 0.0, 1e-6);
  EXPECT_EQ(snapped.x(1), 1.0);

  // A point that breaks a row (x = 1.5 with a = 0: cap_a fails) is not taken: the
  // search branches as before.
  options.equivalent_point = [](const Eigen::VectorXd&, const Eigen::VectorXd&, Eigen::VectorXd* x) {
    SetChoicePoint(x, 1.5, 0.0, 1.0);
    return true;
  };
  const BranchAndBoundResult rejected = SolveBranchAndBound(p, *solver, options);
  ASSERT_EQ(rejected.status, SolveStatus::kOptimal);
  EXPECT_EQ(rejected.equivalent_points, 0);
  EXPECT_EQ(rejected.nodes, plain.nodes);
}

TEST(BranchAndBound, AProposalThatIsAPlanIsKeptWhenNoTimeIsLeftForItsQp) {
  // A heuristic that uses up the time (as relax-and-fix may) and returns a complete
  // plan: the search keeps it although no time is left to solve the proposal's QP. The
  // limit leaves the root's relaxation ample time on a loaded machine (with 0.05 s it
  // sometimes ran out before the heuristic was called); the heuristic sleeps past it.
  const auto solver = MakeIpoptRelaxationSolver();
  BranchAndBoundOptions options;
  options.time_limit_s = 2.0;
  const auto past_the_limit = std::chrono::steady_clock::now() + std::chrono::milliseconds(2100);
  const RoundingHeuristic slow = [past_the_limit](const Eigen::VectorXd& relaxed) {
    std::this_thread::sleep_until(past_the_limit);
    Eigen::VectorXd x = relaxed;
    x << 1, 1, 0;
    return std::vector<Eigen::VectorXd>{x};
  };
  const BranchAndBoundResult r = SolveBranchAndBound(Knapsack().problem, *solver, options, slow);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit);
  ASSERT_EQ(r.x.size(), 3);
  EXPECT_NEAR(r.objective, -9.0, 1e-6);
}

// The root heuristic of DecoyInterval returns the optimum (h_b = 1, y = 2.2); its calls
// and the first entry (y) of the point it was given are recorded.
struct RecordedRootHeuristic {
  int calls = 0;
  double given_y = 0.0;
  BranchAndBoundResult result;
};

RecordedRootHeuristic SolveWithRootHeuristic(const Miqp& problem, const Eigen::VectorXd& plan, int after_nodes,
                                             int max_nodes, double wait_gap = kInfinity) {
  const auto solver = MakeInteriorPointRelaxationSolver();
  BranchAndBoundOptions options;
  options.time_limit_s = 60.0;  // holds the nodes waited for at any root pace up to 0.6 s
  options.root_heuristic_after_nodes = after_nodes;
  options.root_heuristic_wait_gap = wait_gap;
  options.max_nodes = max_nodes;
  RecordedRootHeuristic recorded;
  options.root_heuristic = [&](const Eigen::VectorXd& relaxed) {
    ++recorded.calls;
    recorded.given_y = relaxed(0);
    return std::vector<Eigen::VectorXd>{plan};
  };
  recorded.result = SolveBranchAndBound(problem, *solver, options);
  return recorded;
}

TEST(BranchAndBound, ARootHeuristicAskedToWaitRunsOnlyIfTheSearchGoesOnThatLong) {
  // DecoyInterval: the root's rounding gives a plan (0.24), the root bound is about 0, so
  // the search branches; the heuristic's plan is the optimum 0.09.
  Eigen::VectorXd optimum(3);
  optimum << 2.2, 0, 1;
  // At the root (0): called there, and the one node ends with the optimum.
  RecordedRootHeuristic r = SolveWithRootHeuristic(DecoyInterval(), optimum, 0, 1);
  EXPECT_EQ(r.calls, 1);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
  // Asked to wait for 2 nodes, a search capped at its root (max_nodes 1) could never
  // reach them: it does not wait, and the heuristic runs at the root.
  r = SolveWithRootHeuristic(DecoyInterval(), optimum, 2, 1);
  EXPECT_EQ(r.calls, 1);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
  // Uncapped, it is called once after the second node, with the root's point (y = 2.5;
  // the children's points have y = 2.2 or 3), and the search proves the optimum.
  r = SolveWithRootHeuristic(DecoyInterval(), optimum, 2, 1000);
  EXPECT_EQ(r.calls, 1);
  EXPECT_NEAR(r.given_y, 2.5, 1e-3);
  EXPECT_EQ(r.result.status, SolveStatus::kOptimal);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
  // A search that proves its optimum before the count never calls it.
  r = SolveWithRootHeuristic(DecoyInterval(), optimum, 100, 1000);
  EXPECT_EQ(r.calls, 0);
  EXPECT_EQ(r.result.status, SolveStatus::kOptimal);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
  EXPECT_LT(r.result.nodes, 100);
}

TEST(BranchAndBound, ARootHeuristicWaitsOnlyForAPlanWithinItsGap) {
  // DecoyInterval's root plan (0.24) lies 0.24 above the root bound (about 0), a relative
  // gap of 0.24 (the objective is below 1): with a wait gap of 0.1 the heuristic runs at
  // the root, with 0.5 it waits for 100 nodes, and the search proves the optimum sooner
  // without it.
  Eigen::VectorXd optimum(3);
  optimum << 2.2, 0, 1;
  RecordedRootHeuristic r = SolveWithRootHeuristic(DecoyInterval(), optimum, 100, 1000, 0.1);
  EXPECT_EQ(r.calls, 1);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
  r = SolveWithRootHeuristic(DecoyInterval(), optimum, 100, 1000, 0.5);
  EXPECT_EQ(r.calls, 0);
  EXPECT_EQ(r.result.status, SolveStatus::kOptimal);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
}

TEST(BranchAndBound, ARootHeuristicDoesNotWaitForMoreNodesThanTheTimeLeftHolds) {
  // Asked to wait for 1e8 nodes, which the 60 s limit cannot hold at the root's pace
  // (over 0.6 microseconds a node): it runs at the root, as with no wait.
  Eigen::VectorXd optimum(3);
  optimum << 2.2, 0, 1;
  const RecordedRootHeuristic r = SolveWithRootHeuristic(DecoyInterval(), optimum, 100000000, 1);
  EXPECT_EQ(r.calls, 1);
  EXPECT_NEAR(r.result.objective, 0.09, 1e-5);
}

TEST(BranchAndBound, ARootHeuristicAskedToWaitRunsAtARootWithoutAPlan) {
  // The knapsack's root roundings give no plan (the simple rounding (1, 1, 1) weighs 6):
  // the heuristic runs at the root however long it was asked to wait.
  Eigen::VectorXd optimum(3);
  optimum << 1, 1, 0;
  const RecordedRootHeuristic r = SolveWithRootHeuristic(Knapsack().problem, optimum, 1000, 1);
  EXPECT_EQ(r.calls, 1);
  EXPECT_NEAR(r.result.objective, -9.0, 1e-6);
}

}  // namespace
}  // namespace mfp
