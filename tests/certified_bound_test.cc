// The search's bounds are what its relaxations certify (RelaxationResult::cost_floor),
// not the objectives at their points: a solver whose floors lie below its objectives
// (an interior point stopped at a coarse dual residual) must not make the search claim
// a tighter gap than those floors prove. Re-certification (recertify_leaves) may raise
// a settled subtree's floor only to what a certifying solve of it proves, and keeps what
// the caller asks of the incumbent (recertify_within).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planner/miqp/miqp_builder.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/lagging_floors.h"

namespace mfp {
namespace {

// Knapsack: max 5a + 4b + 3c + 2d s.t. 2a + 3b + c + 2d <= 5, binaries. Subsets within
// the capacity: {a,b} 9, {a,c,d} 10 (weight 5), {b,c} 7, {a,c} 8, {c,d} 5, ...;
// {a,b,c} weighs 6. Optimum -10 at (1, 0, 1, 1); the relaxation is fractional.
Miqp Knapsack() {
  MiqpBuilder b;
  const int a = b.AddBinary("a"), bb = b.AddBinary("b"), c = b.AddBinary("c"), d = b.AddBinary("d");
  b.AddRow("capacity", LinExpr::Var(a, 2) + LinExpr::Var(bb, 3) + LinExpr::Var(c, 1) + LinExpr::Var(d, 2), -kInfinity,
           5);
  b.AddLinearCost(LinExpr::Var(a, -5) + LinExpr::Var(bb, -4) + LinExpr::Var(c, -3) + LinExpr::Var(d, -2));
  return b.Build();
}

// The interior point, with every solved relaxation's floor put `lag` below its
// objective (still a valid floor, only a weaker one): what a solve that stopped at a
// coarser dual residual certifies.
class LaggingFloorSolver : public RelaxationSolver {
 public:
  explicit LaggingFloorSolver(double lag) : lag_(lag) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    RelaxationResult r = inner_->Solve(problem, request);
    if (r.status == RelaxationStatus::kSolved) {
      r.cost_floor = std::min(r.cost_floor, r.objective - lag_);
      r.bound_floor = std::min(r.bound_floor, r.objective - lag_);
      ++solved;
    }
    return r;
  }
  std::string Name() const override { return "lagging floor"; }
  int solved = 0;

 private:
  double lag_;
  std::unique_ptr<RelaxationSolver> inner_ = MakeInteriorPointRelaxationSolver();
};

// The lagging floors of LaggingFloorSolver, except on re-certification's solves
// (RelaxationRequest::certify_floor), which get the interior point's own certificate.
class LaggingUnlessCertifyingSolver : public RelaxationSolver {
 public:
  explicit LaggingUnlessCertifyingSolver(double lag) : lagging_(lag) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    if (!request.certify_floor) return lagging_.Solve(problem, request);
    ++certifying;
    return exact_->Solve(problem, request);
  }
  std::string Name() const override { return "lagging unless certifying"; }
  int certifying = 0;

 private:
  LaggingFloorSolver lagging_;
  std::unique_ptr<RelaxationSolver> exact_ = MakeInteriorPointRelaxationSolver();
};

BranchAndBoundResult Search(RelaxationSolver* solver, int recertify_leaves = BranchAndBoundOptions().recertify_leaves) {
  BranchAndBoundOptions options;
  options.recertify_leaves = recertify_leaves;
  // Every relaxation is solved to the end, so every floor the search sees is the lagged one
  // (a cutoff's floor is the solver's own).
  options.early_cutoff = false;
  return SolveBranchAndBound(Knapsack(), *solver, options);
}

TEST(CertifiedBound, FloorsBelowTheObjectivesBoundTheGapTheSearchClaims) {
  // Each floor 0.05 below its objective, against a gap tolerance of 1e-4 x 10 = 1e-3:
  // the subtree of the optimum (-10) is certified only down to -10.05, so no bound above
  // that is proven, and the search cannot call the plan optimal to its 1e-4.
  constexpr double kLag = 0.05;
  LaggingFloorSolver solver(kLag);
  const BranchAndBoundResult r = Search(&solver);
  ASSERT_GT(solver.solved, 0);
  EXPECT_NEAR(r.objective, -10.0, 1e-6);
  EXPECT_NE(r.status, SolveStatus::kOptimal);  // the tree is exhausted, but not to the gap asked
  EXPECT_LE(r.bound, -10.0 - kLag + 1e-6);
  EXPECT_GE(r.gap, kLag / 10.0 - 1e-6);
  EXPECT_NEAR(r.gap, (r.objective - r.bound) / std::abs(r.objective), 1e-12);
  EXPECT_LE(r.root_bound, r.bound + 1e-12);
}

TEST(CertifiedBound, FloorsWithinTheGapToleranceStillProve) {
  // Floors 1e-5 below the objectives, a hundredth of the tolerance: the same optimum,
  // proven, with the claimed bound no higher than the floors allow.
  constexpr double kLag = 1e-5;
  LaggingFloorSolver solver(kLag);
  const BranchAndBoundResult r = Search(&solver);
  EXPECT_EQ(r.status, SolveStatus::kOptimal);
  EXPECT_NEAR(r.objective, -10.0, 1e-6);
  EXPECT_LE(r.bound, -10.0 - kLag + 1e-6);
  EXPECT_LE(r.gap, 1e-4);
}

// The root cut loop's second pass on a fractional root, with lagging floors: whatever it
// proves (reduced-cost fixing against the incumbent may fix every integer, an exact proof),
// the bound it claims never lies above the true optimum, and a plan called optimal is it.
TEST(CertifiedBound, TheRootCutLoopsSecondPassClaimsNoBoundAboveTheOptimum) {
  for (const double lag : {0.05, 0.5, 3.0}) {
    for (const int rounds : {0, 5}) {
      BranchAndBoundOptions options;
      options.early_cutoff = false;
      options.long_search_only = 0;
      options.root_cut_rounds = rounds;
      LaggingFloorSolver solver(lag);
      const BranchAndBoundResult r = SolveBranchAndBound(Knapsack(), solver, options);
      ASSERT_GT(solver.solved, 0) << lag << " " << rounds;
      EXPECT_NEAR(r.objective, -10.0, 1e-6) << lag << " " << rounds;
      EXPECT_LE(r.bound, -10.0 + 1e-9) << lag << " " << rounds;
      EXPECT_LE(r.root_bound, -10.0 - lag + 1e-6) << lag << " " << rounds;
    }
  }
}

// An integral root whose floor misses the gap asked: its tree is exhausted at the root,
// so the root cut loop (which tightens open nodes) and its second pass have nothing to do.
TEST(CertifiedBound, AnIntegralRootShortOfTheGapRunsNoRootCutLoop) {
  // min -a - 2b s.t. a + b <= 2, binaries: the relaxation's optimum (1, 1) is integral.
  MiqpBuilder b;
  const int a = b.AddBinary("a"), bb = b.AddBinary("b");
  b.AddRow("sum", LinExpr::Var(a) + LinExpr::Var(bb), -kInfinity, 2);
  b.AddLinearCost(LinExpr::Var(a, -1) + LinExpr::Var(bb, -2));
  const Miqp problem = b.Build();
  BranchAndBoundOptions options;
  options.early_cutoff = false;
  options.long_search_only = 0;
  int solves_without_cuts = 0;
  for (const int rounds : {0, 5}) {
    options.root_cut_rounds = rounds;
    LaggingFloorSolver solver(0.05);
    const BranchAndBoundResult r = SolveBranchAndBound(problem, solver, options);
    EXPECT_NEAR(r.objective, -3.0, 1e-6) << rounds;
    EXPECT_NE(r.status, SolveStatus::kOptimal) << rounds;
    EXPECT_EQ(r.nodes, 1) << rounds;
    EXPECT_EQ(r.root_cuts, 0) << rounds;
    if (rounds == 0) {
      solves_without_cuts = solver.solved;
    } else {
      EXPECT_EQ(solver.solved, solves_without_cuts);  // no cut round, no second pass
    }
  }
}

// Re-certification (BranchAndBoundOptions::recertify_leaves): an exhausted tree short of
// the gap by lagging floors solves its lowest-floor subtrees again; when those solves
// certify the floors, the search proves its plan, and the bound it claims never lies above
// the optimum, whatever the lag.
TEST(CertifiedBound, ReCertifiedFloorsProveTheExhaustedTreeAndStayBelowTheOptimum) {
  for (const double lag : {0.05, 0.5, 3.0}) {
    LaggingUnlessCertifyingSolver solver(lag);
    const BranchAndBoundResult r = Search(&solver, /*recertify_leaves=*/8);
    EXPECT_NEAR(r.objective, -10.0, 1e-6) << lag;
    EXPECT_EQ(r.status, SolveStatus::kOptimal) << lag;
    EXPECT_LE(r.bound, -10.0 + 1e-9) << lag;
    EXPECT_LE(r.gap, 1e-4) << lag;
    EXPECT_GT(r.floor_recertifications, 0) << lag;
    EXPECT_LE(r.floor_recertifications, 8) << lag;
    EXPECT_EQ(solver.certifying, r.floor_recertifications) << lag;
    EXPECT_GT(r.floors_certified, 0) << lag;
  }
}

// Without it (0), or when the re-certifying solves certify no more than the search's own
// (every solve lags), the same tree stays short of the gap: `feasible`, its bound the lagged one.
TEST(CertifiedBound, WithoutCertifiedFloorsTheExhaustedTreeStaysFeasible) {
  constexpr double kLag = 0.05;
  LaggingUnlessCertifyingSolver off(kLag);
  const BranchAndBoundResult r_off = Search(&off, /*recertify_leaves=*/0);
  EXPECT_EQ(r_off.status, SolveStatus::kFeasible);
  EXPECT_EQ(r_off.floor_recertifications, 0);
  EXPECT_EQ(off.certifying, 0);
  EXPECT_LE(r_off.bound, -10.0 - kLag + 1e-6);
  LaggingFloorSolver lagging(kLag);
  const BranchAndBoundResult r = Search(&lagging, /*recertify_leaves=*/8);
  EXPECT_EQ(r.status, SolveStatus::kFeasible);
  EXPECT_GT(r.floor_recertifications, 0);
  EXPECT_EQ(r.floors_certified, 0);
  EXPECT_LE(r.bound, -10.0 - kLag + 1e-6);
}

// The budget: at most recertify_leaves solves, and as many subtrees kept; a lagging
// subtree not kept keeps its lagged floor, so a budget short of the lagging subtrees
// leaves the gap unproven (and solves nothing: the proof is out of its reach).
TEST(CertifiedBound, ReCertificationSolvesAtMostItsBudget) {
  constexpr double kLag = 3.0;  // the subtrees of {a, b} (9) and {a, c} (8) lag below -10 too
  LaggingUnlessCertifyingSolver all(kLag);
  const BranchAndBoundResult proven = Search(&all, /*recertify_leaves=*/8);
  EXPECT_EQ(proven.status, SolveStatus::kOptimal);
  ASSERT_GE(proven.floor_recertifications, 2) << "the knapsack's tree should settle several lagging subtrees";
  LaggingUnlessCertifyingSolver one(kLag);
  const BranchAndBoundResult r = Search(&one, /*recertify_leaves=*/1);
  EXPECT_LE(r.floor_recertifications, 1);
  EXPECT_EQ(r.status, SolveStatus::kFeasible);
  EXPECT_NEAR(r.objective, -10.0, 1e-6);
  EXPECT_LE(r.bound, -10.0 - 1e-3);
}

// A window's last choice, reduced to two variables: the binary s trims the last step (1:
// the foot stops half way), the final foot f in [0, 1] has its goal at 1, f <= 1 - s / 2,
// and the cost (f - 1)^2 - 0.3 s rewards the goal without demanding it: reaching it costs
// 0, stopping short -0.05, the optimum.
struct StopShortOrReachTheGoal {
  StopShortOrReachTheGoal() {
    MiqpBuilder b;
    s = b.AddBinary("s");
    f = b.AddVariable("f", 0.0, 1.0, false);
    b.AddRow("half way when trimmed", LinExpr::Var(f) + LinExpr::Var(s, 0.5), -kInfinity, 1.0);
    b.AddSquaredCost(LinExpr::Var(f) - LinExpr::Constant(1.0), 1.0);
    b.AddLinearCost(LinExpr::Var(s, -0.3));
    problem = b.Build();
  }
  Miqp problem;
  int s = -1, f = -1;
};

// The interior point as it misled a window's search (cert10's case (b)): every floor 0.01
// below its objective; where s is free, a point stopped early that leans to the goal
// (s = 0.3, f = 0.85, with its own objective, above the relaxation's optimum), so the
// search dives to the goal plan first; where s is fixed to 1, an objective 1 too high, so
// the search prunes the subtree that beats the goal plan. Re-certification's solves
// (certify_floor) are the interior point's own.
class MisledToTheGoalSolver : public RelaxationSolver {
 public:
  explicit MisledToTheGoalSolver(int s, int f) : s_(s), f_(f) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    RelaxationResult r = inner_->Solve(problem, request);
    if (request.certify_floor || r.status != RelaxationStatus::kSolved) return r;
    r.cost_floor = std::min(r.cost_floor, r.objective - 0.01);
    r.bound_floor = std::min(r.bound_floor, r.objective - 0.01);
    const double lower = request.lower.size() ? request.lower(s_) : problem.var_lower(s_);
    const double upper = request.upper.size() ? request.upper(s_) : problem.var_upper(s_);
    if (lower < upper) {
      r.x(s_) = 0.3;
      r.x(f_) = 0.85;
      r.objective = problem.Objective(r.x);
    } else if (lower >= 1.0) {
      r.objective += 1.0;
    }
    return r;
  }
  std::string Name() const override { return "misled to the goal"; }

 private:
  int s_, f_;
  std::unique_ptr<RelaxationSolver> inner_ = MakeInteriorPointRelaxationSolver();
};

// Re-certification re-opens the pruned subtree whose exact optimum beats the incumbent:
// without recertify_within it trades the goal plan for the one that stops short (proven
// optimal); with ranges that keep the foot within 0.1 of its goal once the incumbent is
// there, the goal plan stays and is proven optimal within them.
TEST(CertifiedBound, ReCertificationKeepsWhatTheIncumbentKeeps) {
  const StopShortOrReachTheGoal w;
  BranchAndBoundOptions options;
  options.recertify_leaves = 8;
  options.early_cutoff = false;
  options.rounding_heuristic = false;  // a rounding of the root would find the short plan first
  MisledToTheGoalSolver traded_solver(w.s, w.f);
  const BranchAndBoundResult traded = SolveBranchAndBound(w.problem, traded_solver, options);
  EXPECT_EQ(traded.status, SolveStatus::kOptimal);
  EXPECT_NEAR(traded.objective, -0.05, 1e-6);
  EXPECT_NEAR(traded.x(w.f), 0.5, 1e-4) << "the misled search should have re-opened the short plan";
  EXPECT_FALSE(traded.restricted);
  EXPECT_GT(traded.floor_recertifications, 0);

  int calls = 0;
  options.recertify_within = [&](const Eigen::VectorXd& incumbent) {
    ++calls;
    std::vector<VariableRange> keep;
    if (std::abs(incumbent(w.f) - 1.0) <= 0.1) keep.push_back({w.f, 0.9, 1.1});
    return keep;
  };
  MisledToTheGoalSolver kept_solver(w.s, w.f);
  const BranchAndBoundResult kept = SolveBranchAndBound(w.problem, kept_solver, options);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(kept.status, SolveStatus::kOptimal);
  EXPECT_TRUE(kept.restricted);
  EXPECT_NEAR(kept.objective, 0.0, 1e-6);
  EXPECT_NEAR(kept.x(w.f), 1.0, 1e-4);
  EXPECT_NEAR(kept.x(w.s), 0.0, 1e-9);
  EXPECT_LE(kept.bound, 0.0 + 1e-9);
  EXPECT_GE(kept.bound, -1e-4);  // proven within the ranges, not over the whole problem (-0.05)

  // Ranges the incumbent does not meet restrict nothing: the short plan is taken again.
  options.recertify_within = [&](const Eigen::VectorXd&) { return std::vector<VariableRange>{{w.f, 0.0, 0.6}}; };
  MisledToTheGoalSolver unmet_solver(w.s, w.f);
  const BranchAndBoundResult unmet = SolveBranchAndBound(w.problem, unmet_solver, options);
  EXPECT_FALSE(unmet.restricted);
  EXPECT_NEAR(unmet.objective, -0.05, 1e-6);
}

// The store keeps the lowest floors below the target, up to its capacity; every other
// floor counts by the least of them, so the least floor over all is never lost.
TEST(CertifiedBound, TheLaggingFloorsStoreKeepsTheLowestAndCountsTheRest) {
  LaggingFloors store(2);
  const double target = 10.0;
  for (const double floor : {5.0, 1.0, 12.0, 3.0, 0.0, 4.0}) {
    SettledSubtree s;
    s.floor = floor;
    store.Note(std::move(s), target);
  }
  store.NoteFloor(2.5);  // without a box
  ASSERT_EQ(store.kept().size(), 2u);
  std::vector<double> kept = {store.kept()[0].floor, store.kept()[1].floor};
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(store.rest_floor(), 2.5);
  EXPECT_EQ(store.Least(), 0.0);
  EXPECT_FALSE(store.Keeps(11.0, target));  // at or above the target it never limits
  EXPECT_FALSE(store.Keeps(2.0, target));   // above the highest kept one
  EXPECT_TRUE(store.Keeps(0.5, target));
  LaggingFloors off(0);
  EXPECT_FALSE(off.Keeps(-100.0, target));
}

}  // namespace
}  // namespace mfp
