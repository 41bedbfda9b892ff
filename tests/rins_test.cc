// RINS on a hand-built MIQP with a poor incumbent: two coordinates y0, y1 in [0, 4], each
// in one of three intervals [0, 1], [2, 2.2], [3, 4] chosen by a one-of group (big-M rows,
// M = 4), minimising (y0 - 2.5)^2 + (y1 - 2.5)^2. The incumbent puts both in [0, 1]
// (y = 1: 2.25 + 2.25 = 4.5). A relaxation point that agrees with it on y0's group and not
// on y1's fixes y0's choice: the best plan of that neighbourhood keeps y0 = 1 and moves y1
// to 2.2 (2.25 + 0.09 = 2.34); the global optimum (0.18) lies outside it.
#include "planner/search/internal/rins.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "planner/miqp/miqp_builder.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/search_state.h"

namespace mfp {
namespace {

constexpr int kY[2] = {0, 1};
constexpr int kFirstBinary[2] = {2, 5};  // y_k's group: kFirstBinary[k] + interval

Miqp TwoIntervalChoices() {
  const double lo[3] = {0.0, 2.0, 3.0}, hi[3] = {1.0, 2.2, 4.0};
  const double M = 4.0;
  MiqpBuilder b;
  for (int k = 0; k < 2; ++k) b.AddVariable("y" + std::to_string(k), 0.0, 4.0, false);
  for (int k = 0; k < 2; ++k) {
    std::vector<int> group;
    LinExpr one;
    for (int i = 0; i < 3; ++i) {
      const int h = b.AddBinary("h" + std::to_string(k) + std::to_string(i));
      group.push_back(h);
      one += LinExpr::Var(h);
      const std::string name = std::to_string(k) + std::to_string(i);
      b.AddRow("lo" + name, LinExpr::Var(kY[k]) - LinExpr::Var(h, M), lo[i] - M, kInfinity);
      b.AddRow("hi" + name, LinExpr::Var(kY[k]) + LinExpr::Var(h, M), -kInfinity, hi[i] + M);
    }
    b.AddRow("one" + std::to_string(k), one, 1.0, 1.0);
    b.AddSos1Group(group);
    b.AddSquaredCost(LinExpr::Var(kY[k]) - LinExpr::Constant(2.5), 1.0);
  }
  return b.Build();
}

// Both coordinates at 1 in their first interval.
Eigen::VectorXd PoorIncumbent() {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(8);
  for (int k = 0; k < 2; ++k) {
    x(kY[k]) = 1.0;
    x(kFirstBinary[k]) = 1.0;
  }
  return x;
}

// Agrees with the incumbent on y0's group, not on y1's.
Eigen::VectorXd RelaxationPoint() {
  Eigen::VectorXd x = PoorIncumbent();
  x(kY[1]) = 2.5;
  x(kFirstBinary[1]) = 0.3;
  x(kFirstBinary[1] + 1) = 0.3;
  x(kFirstBinary[1] + 2) = 0.4;
  return x;
}

TEST(Rins, ImprovesAPoorIncumbentWithinTheNeighbourhoodWhereItAgreesWithTheRelaxation) {
  const Miqp p = TwoIntervalChoices();
  ASSERT_EQ(p.num_variables(), 8);
  const auto solver = MakeInteriorPointRelaxationSolver();
  const std::vector<RelaxationSolver*> solvers = {solver.get()};
  BranchAndBoundOptions options;
  options.rins_max_nodes = 50;
  SearchState state(p, solvers, options);
  state.OfferIncumbent(PoorIncumbent());
  ASSERT_NEAR(state.result().objective, 4.5, 1e-9);

  const RinsOutcome outcome = RunRins(&state, RelaxationPoint(), nullptr);
  EXPECT_TRUE(outcome.ran);
  EXPECT_TRUE(outcome.improved);
  EXPECT_EQ(outcome.fixed, 3);  // y0's group
  EXPECT_GE(outcome.nodes, 1);
  EXPECT_NEAR(state.result().objective, 2.34, 1e-5);
  const Eigen::VectorXd& x = state.result().x;
  EXPECT_NEAR(x(kY[0]), 1.0, 1e-5);  // the fixed choice kept
  EXPECT_NEAR(x(kFirstBinary[0]), 1.0, 1e-9);
  EXPECT_NEAR(x(kY[1]), 2.2, 1e-5);
  EXPECT_NEAR(x(kFirstBinary[1] + 1), 1.0, 1e-9);
}

TEST(Rins, DoesNotRunWhenTooFewOrAllIntegersAgreeOrWithoutAnIncumbent) {
  const Miqp p = TwoIntervalChoices();
  const auto solver = MakeInteriorPointRelaxationSolver();
  const std::vector<RelaxationSolver*> solvers = {solver.get()};
  BranchAndBoundOptions options;
  {
    SearchState state(p, solvers, options);
    EXPECT_FALSE(RunRins(&state, RelaxationPoint(), nullptr).ran);  // no incumbent
  }
  SearchState state(p, solvers, options);
  state.OfferIncumbent(PoorIncumbent());
  EXPECT_FALSE(RunRins(&state, PoorIncumbent(), nullptr).ran);  // all agree: nothing to search
  options.rins_min_fixed_fraction = 0.75;                        // 3 of 6 agree
  SearchState strict(p, solvers, options);
  strict.OfferIncumbent(PoorIncumbent());
  EXPECT_FALSE(RunRins(&strict, RelaxationPoint(), nullptr).ran);
  EXPECT_NEAR(strict.result().objective, 4.5, 1e-9);
}

TEST(Rins, AnExpiredDeadlineLeavesTheIncumbent) {
  const Miqp p = TwoIntervalChoices();
  const auto solver = MakeInteriorPointRelaxationSolver();
  const std::vector<RelaxationSolver*> solvers = {solver.get()};
  BranchAndBoundOptions options;
  options.deadline = Deadline::After(0.0);
  SearchState state(p, solvers, options);
  state.OfferIncumbent(PoorIncumbent());
  EXPECT_FALSE(RunRins(&state, RelaxationPoint(), nullptr).ran);
  EXPECT_NEAR(state.result().objective, 4.5, 1e-9);
}

}  // namespace
}  // namespace mfp
