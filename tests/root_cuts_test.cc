// The root cut loop's c-MIR cuts are valid: on a hand-built MIQP (one foot position, a
// one-of choice of three stones by big-M rows, a one-of choice of a side) every cut holds
// at every vertex of every integer assignment's polygon, found by enumerating the integer
// points and the polygons' vertices; on the Table I instances the proven optimum meets
// every cut row and the search with cuts proves the same optimum.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/planning/internal/exact_window.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/implied_cuts.h"
#include "planner/search/internal/mir_cuts.h"
#include "planner/search/internal/root_cuts.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

// Variables: px, py (continuous, in [-2, 2]), H0..H2 (stones), S0, S1 (side of x = 0).
// Stone r is the box [xmin, xmax] x [ymin, ymax], enforced by big-M rows when H_r = 1;
// S0 = 1 means px <= 0, S1 = 1 means px >= 0. The objective pulls the foot to (0.1, -1.6),
// outside the hull of the stones (whose y >= -1); the big-M rows (M = 4, looser than the
// box needs) let the relaxation reach it by spreading H.
Miqp StonesInstance() {
  const double M = 4.0;  // the box [-2, 2]^2 bounds every row's violation
  struct Box {
    double xmin, xmax, ymin, ymax;
  };
  const std::vector<Box> stones = {{-1.5, -0.5, -1.0, 1.0}, {0.5, 1.5, -1.0, 0.2}, {-0.3, 0.35, 0.8, 1.5}};
  MiqpBuilder b;
  const int px = b.AddVariable("px", -2.0, 2.0, false), py = b.AddVariable("py", -2.0, 2.0, false);
  std::vector<int> h;
  for (int r = 0; r < 3; ++r) h.push_back(b.AddBinary("H" + std::to_string(r)));
  const int s0 = b.AddBinary("S0"), s1 = b.AddBinary("S1");
  // (px - 0.1)^2 + (py + 1.6)^2 without its constant.
  b.AddSquaredCost(LinExpr::Var(px), 1.0);
  b.AddSquaredCost(LinExpr::Var(py), 1.0);
  b.AddLinearCost(LinExpr::Var(px, -0.2) + LinExpr::Var(py, 3.2));
  for (int r = 0; r < 3; ++r) {
    const Box& box = stones[r];
    const std::string stone = "stone" + std::to_string(r);
    const LinExpr big_m = LinExpr::Var(h[r], M);
    b.AddRow(stone + "_xmax", LinExpr::Var(px) + big_m, -kInfinity, box.xmax + M);  // px <= xmax + M (1 - H)
    b.AddRow(stone + "_xmin", LinExpr::Var(px, -1.0) + big_m, -kInfinity, -box.xmin + M);  // px >= xmin - M (1 - H)
    b.AddRow(stone + "_ymax", LinExpr::Var(py) + big_m, -kInfinity, box.ymax + M);
    b.AddRow(stone + "_ymin", LinExpr::Var(py, -1.0) + big_m, -kInfinity, -box.ymin + M);
  }
  b.AddRow("one_stone", LinExpr::Var(h[0]) + LinExpr::Var(h[1]) + LinExpr::Var(h[2]), 1.0, 1.0);
  b.AddRow("side0", LinExpr::Var(px) + LinExpr::Var(s0, 2.0), -kInfinity, 2.0);        // px <= 2 (1 - S0)
  b.AddRow("side1", LinExpr::Var(px, -1.0) + LinExpr::Var(s1, 2.0), -kInfinity, 2.0);  // px >= -2 (1 - S1)
  b.AddRow("one_side", LinExpr::Var(s0) + LinExpr::Var(s1), 1.0, 1.0);
  b.AddSos1Group(h);
  b.AddSos1Group({s0, s1});
  return b.Build();
}

// The vertices of {(px, py) : rows and bounds of p with the integers fixed to z}: every
// pair of constraint lines' intersection that meets all constraints.
std::vector<Eigen::VectorXd> Vertices(const Miqp& p, const Eigen::VectorXd& z) {
  struct Line {
    double a, b, c;  // a px + b py = c
  };
  std::vector<Line> lines = {{1, 0, p.var_lower(0)}, {1, 0, p.var_upper(0)}, {0, 1, p.var_lower(1)},
                             {0, 1, p.var_upper(1)}};
  for (int i = 0; i < p.num_rows(); ++i) {
    Eigen::VectorXd x = z;
    x(0) = x(1) = 0.0;
    const double fixed = p.A.row(i).dot(x);
    const double a = p.A.coeff(i, 0), b = p.A.coeff(i, 1);
    if (a == 0.0 && b == 0.0) continue;
    for (double bound : {p.row_lower(i), p.row_upper(i)}) {
      if (std::isfinite(bound)) lines.push_back({a, b, bound - fixed});
    }
  }
  std::vector<Eigen::VectorXd> vertices;
  for (size_t i = 0; i < lines.size(); ++i) {
    for (size_t k = i + 1; k < lines.size(); ++k) {
      const double det = lines[i].a * lines[k].b - lines[i].b * lines[k].a;
      if (std::abs(det) < 1e-12) continue;
      Eigen::VectorXd x = z;
      x(0) = (lines[i].c * lines[k].b - lines[i].b * lines[k].c) / det;
      x(1) = (lines[i].a * lines[k].c - lines[i].c * lines[k].a) / det;
      if (p.MaxViolation(x) <= 1e-9) vertices.push_back(x);
    }
  }
  return vertices;
}

// Every integer assignment of the 0/1 variables 2..6 (all 32, feasible or not).
std::vector<Eigen::VectorXd> IntegerPoints() {
  std::vector<Eigen::VectorXd> points;
  for (int bits = 0; bits < 32; ++bits) {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(7);
    for (int k = 0; k < 5; ++k) z(2 + k) = (bits >> k) & 1;
    points.push_back(z);
  }
  return points;
}

// Every cut row of q (rows from p.num_rows() on) holds at every vertex of every integer
// assignment's polygon of p.
void ExpectCutsHoldAtEveryVertex(const Miqp& p, const Miqp& q) {
  int vertices_checked = 0;
  for (const Eigen::VectorXd& z : IntegerPoints()) {
    for (const Eigen::VectorXd& v : Vertices(p, z)) {
      ++vertices_checked;
      const Eigen::VectorXd activity = q.A * v;
      for (int i = p.num_rows(); i < q.num_rows(); ++i) {
        EXPECT_LE(activity(i), q.row_upper(i) + 1e-9) << q.row_names[i] << " cuts off a feasible vertex";
      }
    }
  }
  EXPECT_GT(vertices_checked, 0);
}

TEST(RootCuts, EveryCutHoldsAtEveryVertexOfEveryIntegerAssignment) {
  const Miqp p = StonesInstance();
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(RelaxationBackend::kInteriorPointWithIpoptFallback, 1);
  BranchAndBoundOptions options;
  options.root_cut_rounds = 10;
  const RootCutLoopResult loop = RunRootCutLoop(p, *solvers.workers().front(), options, Deadline());
  ASSERT_GT(loop.cuts, 0) << "no cut separated: the instance no longer tests anything";
  EXPECT_GT(loop.bound_after, loop.bound_before);
  ExpectCutsHoldAtEveryVertex(p, loop.problem);
  // The search with the cuts proves the optimum of the search without them.
  BranchAndBoundOptions plain;
  const BranchAndBoundResult without = SolveBranchAndBound(p, *solvers.workers().front(), plain);
  const BranchAndBoundResult with = SolveBranchAndBound(p, *solvers.workers().front(), options);
  ASSERT_EQ(without.status, SolveStatus::kOptimal);
  ASSERT_EQ(with.status, SolveStatus::kOptimal);
  EXPECT_NEAR(with.objective, without.objective, 1e-6);
  EXPECT_EQ(with.root_cuts, loop.cuts);
  EXPECT_GT(with.root_bound, with.root_bound_before_cuts);
}

TEST(RootCuts, ImpliedBoundCutsHoldAtEveryVertexOfEveryIntegerAssignment) {
  const Miqp p = StonesInstance();
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(RelaxationBackend::kInteriorPointWithIpoptFallback, 1);
  BranchAndBoundOptions options;
  options.root_cut_rounds = 10;
  options.root_cut_families = kImpliedBoundCuts;
  const RootCutLoopResult loop = RunRootCutLoop(p, *solvers.workers().front(), options, Deadline());
  ASSERT_GT(loop.cuts, 0) << "no implied-bound cut separated: the instance no longer tests anything";
  EXPECT_GT(loop.bound_after, loop.bound_before);
  ExpectCutsHoldAtEveryVertex(p, loop.problem);
}

// Appends cut as a row "cut" (<= side) to q.
void AppendRow(const LinearCut& cut, Miqp* q) {
  const int i = q->num_rows();
  std::vector<Eigen::Triplet<double>> triplets;
  for (int r = 0; r < i; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(q->A, r); it; ++it) {
      triplets.emplace_back(r, static_cast<int>(it.col()), it.value());
    }
  }
  for (const auto& [j, c] : cut.coefficients) triplets.emplace_back(i, j, c);
  q->A.resize(i + 1, q->num_variables());
  q->A.setFromTriplets(triplets.begin(), triplets.end());
  q->row_lower.conservativeResize(i + 1);
  q->row_upper.conservativeResize(i + 1);
  q->row_lower(i) = -kInfinity;
  q->row_upper(i) = cut.rhs;
  q->row_names.push_back("cut");
}

// Probing finds the conflicts the stones imply (S0 = 1 puts the foot at px <= 0, away
// from stone 1; S1 = 1 away from stone 0), and a clique cut over them is separated at a
// point that takes both and holds at every vertex.
TEST(RootCuts, CliqueCutsFromProbingConflictsHoldAtEveryVertex) {
  const Miqp p = StonesInstance();
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  const RootProbing probing = ProbeRootBinaries(p, lower, upper);
  const int h0 = 2, h1 = 3, s0 = 5, s1 = 6;
  auto conflicts_of = [&](int z) {
    for (const ProbedBinary& b : probing.binaries) {
      if (b.z == z) return b.conflicts;
    }
    return std::vector<int>{};
  };
  const std::vector<int> of_s0 = conflicts_of(s0), of_s1 = conflicts_of(s1);
  EXPECT_NE(std::find(of_s0.begin(), of_s0.end(), h1), of_s0.end());
  EXPECT_NE(std::find(of_s1.begin(), of_s1.end(), h0), of_s1.end());
  EXPECT_EQ(std::find(of_s0.begin(), of_s0.end(), h0), of_s0.end()) << "stone 0 lies at px <= 0: no conflict";
  Eigen::VectorXd x = Eigen::VectorXd::Zero(7);
  x(h1) = 0.6;
  x(s0) = 0.6;
  const std::vector<LinearCut> cuts = SeparateCliqueCuts(probing, x, 1e-4);
  ASSERT_FALSE(cuts.empty());
  EXPECT_GT(cuts.front().Activity(x), cuts.front().rhs);
  Miqp q = p;
  for (const LinearCut& cut : cuts) AppendRow(cut, &q);
  ExpectCutsHoldAtEveryVertex(p, q);
}

// A Table I instance: the optimum proven without cuts meets every cut row of the loop,
// and the search with cuts ends at the same objective.
void ExpectOptimumMeetsCuts(const std::string& scenario, int steps) {
  const Course c = LoadTableICourse(scenario, steps);
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  const Miqp& m = formulation.miqp();
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(RelaxationBackend::kInteriorPointWithIpoptFallback, 1);
  BranchAndBoundOptions bnb = c.scenario.options.branch_and_bound;
  bnb.time_limit_s = 120.0;
  const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) { return formulation.RoundAlongPlan(relaxed); };
  bnb.root_cut_rounds = 0;
  const BranchAndBoundResult without = SolveBranchAndBound(m, solvers.workers(), bnb, rounding);
  ASSERT_EQ(without.status, SolveStatus::kOptimal);
  bnb.root_cut_rounds = 5;
  const RootCutLoopResult loop = RunRootCutLoop(m, *solvers.workers().front(), bnb, Deadline());
  EXPECT_GT(loop.cuts, 0);
  const Eigen::VectorXd activity = loop.problem.A * without.x;
  for (int i = m.num_rows(); i < loop.problem.num_rows(); ++i) {
    EXPECT_LE(activity(i), loop.problem.row_upper(i) + 1e-6) << loop.problem.row_names[i] << " cuts off the optimum";
  }
  // Given the optimum's objective as the plan in hand, the loop's reduced-cost fixing and
  // probing keep the optimum within the problem's bounds, and its cuts hold there.
  const RootCutLoopResult after_plan = RunRootCutLoop(m, *solvers.workers().front(), bnb, Deadline(), without.objective);
  const Miqp& fixed = after_plan.problem;
  EXPECT_LE((fixed.var_lower - without.x).maxCoeff(), 1e-6) << "the optimum is below a fixed lower bound";
  EXPECT_LE((without.x - fixed.var_upper).maxCoeff(), 1e-6) << "the optimum is above a fixed upper bound";
  const Eigen::VectorXd fixed_activity = fixed.A * without.x;
  for (int i = m.num_rows(); i < fixed.num_rows(); ++i) {
    EXPECT_LE(fixed_activity(i), fixed.row_upper(i) + 1e-6) << fixed.row_names[i] << " cuts off the optimum";
  }
  // The loop runs after the root's roundings: the first plan is the one found without it,
  // after the same relaxations.
  std::vector<BranchAndBoundResult> first_reports;
  bnb.on_incumbent = [&first_reports](const BranchAndBoundResult& so_far) {
    if (first_reports.size() < 2) first_reports.push_back(so_far);
  };
  const BranchAndBoundResult with = SolveBranchAndBound(m, solvers.workers(), bnb, rounding);
  ASSERT_EQ(with.status, SolveStatus::kOptimal);
  EXPECT_NEAR(with.objective, without.objective, 1e-4 * std::abs(without.objective));
  EXPECT_GT(with.root_cuts, 0);
  std::vector<BranchAndBoundResult> plain_reports;
  bnb.root_cut_rounds = 0;
  bnb.on_incumbent = [&plain_reports](const BranchAndBoundResult& so_far) {
    if (plain_reports.empty()) plain_reports.push_back(so_far);
  };
  SolveBranchAndBound(m, solvers.workers(), bnb, rounding);
  ASSERT_FALSE(first_reports.empty());
  ASSERT_FALSE(plain_reports.empty());
  EXPECT_EQ(first_reports.front().objective, plain_reports.front().objective);
  EXPECT_EQ(first_reports.front().relaxations, plain_reports.front().relaxations);
}

TEST(RootCuts, LittleDog12OptimumMeetsEveryCut) { ExpectOptimumMeetsCuts("littledog_stepping_stones_45.yaml", 12); }

TEST(RootCuts, Hexapod12OptimumMeetsEveryCut) { ExpectOptimumMeetsCuts("hexapod_stepping_stones_45.yaml", 12); }

}  // namespace
}  // namespace mfp
