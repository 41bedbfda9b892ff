// When RINS runs (RinsSchedule: the wait for nodes without a better plan, the back-off,
// the gap gate), and what its depth-first sub-search gives on Table I's LittleDog 12 from
// a poor plan: a feasible plan no worse than that plan, within the neighbourhood RINS
// fixed.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/qp/fixed_integer_qp.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/rins.h"
#include "planner/search/internal/search_state.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

// min (y - 0.5)^2 over y in [0, 1] with one binary z, y <= z: any plan has objective 0.25
// (z = 0) or 0 (z = 1, y = 0.5).
Miqp OneSwitch() {
  MiqpBuilder b;
  const int y = b.AddVariable("y", 0.0, 1.0, false);
  const int z = b.AddBinary("z");
  b.AddRow("y_if_z", LinExpr::Var(y) - LinExpr::Var(z), -kInfinity, 0.0);
  b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(0.5), 1.0);
  return b.Build();
}

// A state holding the plan z = 0 (objective 0.25) after `nodes` nodes, the bound in
// flight at `bound` (what the search sets while it processes a node).
struct PlanHeld {
  PlanHeld(const Miqp& p, const BranchAndBoundOptions& o, int nodes, double bound)
      : solver(MakeInteriorPointRelaxationSolver()), solvers{solver.get()}, state(p, solvers, o) {
    state.result().nodes = nodes;
    state.OfferIncumbent(Eigen::Vector2d(0.0, 0.0));
    state.SetInFlightBound(bound);
  }
  std::unique_ptr<RelaxationSolver> solver;
  std::vector<RelaxationSolver*> solvers;
  SearchState state;
};

BranchAndBoundOptions Scheduled() {
  BranchAndBoundOptions o;
  o.rins_frequency = 10;
  o.rins_after_nodes = 50;
  o.rins_backoff = 2.0;
  o.rins_min_gap = 0.05;
  return o;
}

TEST(RinsSchedule, TheFirstRunWaitsForNodesWithoutABetterPlan) {
  const Miqp p = OneSwitch();
  const BranchAndBoundOptions o = Scheduled();
  PlanHeld held(p, o, /*nodes=*/100, /*bound=*/0.0);  // the plan found at node 100
  RinsSchedule schedule(o);
  EXPECT_FALSE(schedule.DueAtRoot(held.state));  // rins_after_nodes > 0: never at the root
  held.state.result().nodes = 149;
  EXPECT_FALSE(schedule.DueAtNode(held.state));  // 49 nodes without a better plan
  held.state.result().nodes = 150;
  EXPECT_TRUE(schedule.DueAtNode(held.state));
  BranchAndBoundOptions at_root = o;
  at_root.rins_after_nodes = 0;
  EXPECT_TRUE(RinsSchedule(at_root).DueAtRoot(held.state));
  BranchAndBoundOptions off = o;
  off.rins_frequency = 0;
  EXPECT_FALSE(RinsSchedule(off).DueAtNode(held.state));
}

TEST(RinsSchedule, RunsWithoutABetterPlanDoubleTheIntervalAndOneThatFindsItRestoresIt) {
  const Miqp p = OneSwitch();
  const BranchAndBoundOptions o = Scheduled();
  PlanHeld held(p, o, 0, 0.0);
  RinsSchedule schedule(o);
  RinsOutcome failed;
  failed.ran = true;
  int& nodes = held.state.result().nodes;
  nodes = 50;
  ASSERT_TRUE(schedule.DueAtNode(held.state));
  schedule.Record(held.state, failed, 0.25);  // interval 20
  nodes = 69;
  EXPECT_FALSE(schedule.DueAtNode(held.state));
  nodes = 70;
  ASSERT_TRUE(schedule.DueAtNode(held.state));
  schedule.Record(held.state, failed, 0.25);  // interval 40
  nodes = 109;
  EXPECT_FALSE(schedule.DueAtNode(held.state));
  nodes = 110;
  ASSERT_TRUE(schedule.DueAtNode(held.state));
  // A run that did not start (too few integers agree) leaves the interval as it was.
  schedule.Record(held.state, RinsOutcome(), 0.25);
  nodes = 149;
  EXPECT_FALSE(schedule.DueAtNode(held.state));
  nodes = 150;
  ASSERT_TRUE(schedule.DueAtNode(held.state));
  // A run that found a better plan: the interval is rins_frequency again.
  held.state.OfferIncumbent(Eigen::Vector2d(0.1, 1.0));  // objective 0.16
  RinsOutcome improved;
  improved.ran = improved.improved = true;
  schedule.Record(held.state, improved, 0.25);
  nodes = 159;
  EXPECT_FALSE(schedule.DueAtNode(held.state));
  nodes = 160;
  EXPECT_TRUE(schedule.DueAtNode(held.state));
}

TEST(RinsSchedule, NotWhileTheGapIsAtMostTheMinimum) {
  const Miqp p = OneSwitch();
  const BranchAndBoundOptions o = Scheduled();
  // The plan's objective 0.25 against a bound 0.21: a gap of 0.04 (relative to
  // max(1, |0.25|)), below rins_min_gap.
  PlanHeld close(p, o, 100, 0.21);
  close.state.result().nodes = 200;
  EXPECT_FALSE(RinsSchedule(o).DueAtNode(close.state));
  PlanHeld far(p, o, 100, 0.19);  // 0.06
  far.state.result().nodes = 200;
  EXPECT_TRUE(RinsSchedule(o).DueAtNode(far.state));
}

// LittleDog 12 of Table I: its root relaxation, and the poorer of the root's roundings
// along the plan, completed, as the plan in hand; RINS from there with the default
// options (a depth-first sub-search).
TEST(RinsOnTableI, ADepthFirstSubSearchGivesAFeasiblePlanNoWorseThanItsStartWithinItsNeighbourhood) {
  const Course c = LoadTableICourse("littledog_stepping_stones_45.yaml", 12);
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  const Miqp& p = formulation.miqp();
  BranchAndBoundOptions options = c.scenario.options.branch_and_bound;
  ASSERT_EQ(options.rins_node_selection, NodeSelection::kDepthFirst);
  options.rins_min_fixed_fraction = 0.0;  // run from whatever agrees
  const auto solver = MakeInteriorPointRelaxationSolver();
  const std::vector<RelaxationSolver*> solvers = {solver.get()};
  SearchState state(p, solvers, options);
  const RelaxationResult root = state.SolveWith(*solver, p.var_lower, p.var_upper, nullptr);
  ASSERT_EQ(root.status, RelaxationStatus::kSolved);
  // The poorest completed rounding along the plan: the start RINS must not end above.
  double start = -kInfinity;
  Eigen::VectorXd start_x;
  for (const Eigen::VectorXd& proposal : formulation.RoundAlongPlan(root.x)) {
    const RelaxationResult completed =
        SolveWithIntegersFixed(p, proposal, *solver, state.Request(p.var_lower, p.var_upper, &root.x));
    if (completed.status == RelaxationStatus::kSolved && completed.objective > start) {
      start = completed.objective;
      start_x = completed.x;
    }
  }
  ASSERT_GT(start_x.size(), 0) << "no rounding of the root completes";
  state.OfferIncumbent(start_x, false);
  ASSERT_NEAR(state.result().objective, start, 1e-6 * std::abs(start));
  const RinsOutcome outcome = RunRins(&state, root.x, nullptr);
  ASSERT_TRUE(outcome.ran);
  EXPECT_GT(outcome.fixed, 0);
  EXPECT_GE(outcome.nodes, 1);
  EXPECT_LE(outcome.nodes, options.rins_max_nodes);
  const Eigen::VectorXd& x = state.result().x;
  EXPECT_LE(state.result().objective, start + 1e-9 * std::abs(start));
  // Here it does better: the start (2938.10, the rounding that trims) leaves the
  // neighbourhood a plan of 2298.61 (the optimum is 2291.77), which the sub-search finds.
  EXPECT_LT(state.result().objective, 0.8 * start);
  EXPECT_LE(p.MaxViolationOfRows(x), options.feasibility_tolerance);
  // Within the neighbourhood: the integers fixed (where the root and the start agree) keep
  // the start's values.
  for (int j = 0; j < p.num_variables(); ++j) {
    if (p.is_integer[j] && std::abs(root.x(j) - start_x(j)) <= options.rins_agreement) {
      EXPECT_NEAR(x(j), std::round(start_x(j)), 1e-9) << p.var_names[j];
    }
  }
}

}  // namespace
}  // namespace mfp
