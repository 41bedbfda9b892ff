// The long-search rule (BranchAndBoundOptions::long_search_only and the two thresholds):
// the levers kept to long searches run only once the search has passed K nodes and its
// time left holds enough nodes at its pace; a search that ends sooner runs exactly as
// with the levers off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "planner/qp/internal/ipopt_relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_qps.h"

namespace mfp {
namespace {

BranchAndBoundOptions Quiet() {
  BranchAndBoundOptions options;
  options.time_limit_s = 30.0;
  options.rounding_heuristic = false;  // the search's own dives find the plans
  options.group_probing = false;       // the levers are each test's own (probing is on by default)
  options.group_probing_work = 0.0;
  options.rins_frequency = 0;          // RINS too (on by default)
  return options;
}

BranchAndBoundResult Solve(const BranchAndBoundOptions& options) {
  const auto solver = MakeIpoptRelaxationSolver();
  return SolveBranchAndBound(IntervalChain(10), *solver, options);
}

// The levers on and kept to long searches, with the thresholds K and N.
BranchAndBoundOptions Kept(int min_nodes, double nodes_left) {
  BranchAndBoundOptions options = Quiet();
  options.group_probing = true;
  options.rins_frequency = 1;
  options.rins_after_nodes = 0;  // from the root, at every node, whatever the gap (the rule alone decides)
  options.rins_backoff = 1.0;
  options.rins_min_gap = 0.0;
  options.rins_min_fixed_fraction = 0.0;
  options.long_search_only = kLongSearchProbing | kLongSearchRins;
  options.long_search_min_nodes = min_nodes;
  options.long_search_nodes_left = nodes_left;
  return options;
}

TEST(LongSearch, TheChainNeedsASearch) {
  const BranchAndBoundResult off = Solve(Quiet());
  ASSERT_EQ(off.status, SolveStatus::kOptimal);
  EXPECT_GE(off.nodes, 12);  // else the tests below would not tell K nodes from the end
}

TEST(LongSearch, ASearchEndingBeforeKNodesNeverProbesNorRunsRins) {
  const BranchAndBoundResult off = Solve(Quiet());
  const BranchAndBoundResult kept = Solve(Kept(/*min_nodes=*/100000, /*nodes_left=*/0.0));
  EXPECT_EQ(kept.probed_nodes, 0);
  EXPECT_EQ(kept.rins_runs, 0);
  EXPECT_EQ(kept.rins_nodes, 0);
  // The same search as with the levers off: the same nodes, plan and bound.
  EXPECT_EQ(kept.nodes, off.nodes);
  EXPECT_EQ(kept.relaxations, off.relaxations);
  EXPECT_EQ(ToString(kept.status), ToString(off.status));
  EXPECT_DOUBLE_EQ(kept.objective, off.objective);
}

TEST(LongSearch, TheLeversStartOnceTheSearchHasPassedKNodes) {
  const BranchAndBoundResult always = Solve(Kept(0, 0.0));
  const BranchAndBoundResult after = Solve(Kept(4, 0.0));
  const BranchAndBoundResult off = Solve(Quiet());
  ASSERT_EQ(always.status, SolveStatus::kOptimal);
  ASSERT_EQ(after.status, SolveStatus::kOptimal);
  EXPECT_NEAR(always.objective, off.objective, 1e-4 * std::max(1.0, std::abs(off.objective)));
  EXPECT_NEAR(after.objective, off.objective, 1e-4 * std::max(1.0, std::abs(off.objective)));
  // From the root on, a node is probed at every level; after 4 nodes, some are and fewer.
  EXPECT_GE(always.probed_nodes, 1);
  EXPECT_GE(after.probed_nodes, 1);
  EXPECT_LT(after.probed_nodes, always.probed_nodes);
  EXPECT_LE(after.probed_nodes, after.nodes - 4);
  // RINS (asked at every node; it runs where enough integers agree) from the root on, and
  // after 4 nodes too, at most as often.
  EXPECT_GE(always.rins_runs, 1);
  EXPECT_GE(after.rins_runs, 1);
  EXPECT_LE(after.rins_runs, always.rins_runs);
}

TEST(LongSearch, ASearchWhoseTimeLeftHoldsTooFewNodesIsNeverLong) {
  // 30 s at this search's pace (well under a second per node) holds far fewer than 1e12
  // nodes: never long. With 1 node required it is long from the root, as with no rule.
  const BranchAndBoundResult short_share = Solve(Kept(0, 1e12));
  EXPECT_EQ(short_share.probed_nodes, 0);
  EXPECT_EQ(short_share.rins_runs, 0);
  EXPECT_EQ(short_share.nodes, Solve(Quiet()).nodes);
  BranchAndBoundOptions unruled = Kept(0, 1.0);
  unruled.long_search_only = 0;
  const BranchAndBoundResult long_share = Solve(Kept(0, 1.0));
  const BranchAndBoundResult no_rule = Solve(unruled);
  EXPECT_EQ(long_share.probed_nodes, no_rule.probed_nodes);
  EXPECT_EQ(long_share.rins_runs, no_rule.rins_runs);
  EXPECT_EQ(long_share.nodes, no_rule.nodes);
}

TEST(LongSearch, TheRootCutLoopWaitsForALongSearch) {
  BranchAndBoundOptions cuts = Quiet();
  cuts.rounding_heuristic = true;  // the loop needs the first pass's plan
  cuts.root_cut_rounds = 10;
  BranchAndBoundOptions no_cuts = cuts;
  no_cuts.root_cut_rounds = 0;
  // Kept to long searches that this one never becomes: the search without cuts.
  BranchAndBoundOptions never = cuts;
  never.long_search_only = kLongSearchRootCuts;
  never.long_search_min_nodes = 100000;
  const BranchAndBoundResult plain = Solve(no_cuts);
  const BranchAndBoundResult waited = Solve(never);
  EXPECT_EQ(waited.root_cuts, 0);
  EXPECT_EQ(waited.nodes, plain.nodes);
  EXPECT_DOUBLE_EQ(waited.objective, plain.objective);
  // Long from the root, whose roundings find no plan on this chain: without the rule the
  // loop never runs (it needs a plan), with it the first pass goes on until it holds one,
  // then the loop runs and the search with cuts proves the same optimum.
  BranchAndBoundOptions at_root = cuts;
  at_root.long_search_only = kLongSearchRootCuts;
  at_root.long_search_nodes_left = 0.0;
  const BranchAndBoundResult ruled = Solve(at_root);
  const BranchAndBoundResult unruled = Solve(cuts);
  EXPECT_EQ(unruled.root_cuts, 0);
  EXPECT_GT(ruled.root_cuts, 0);
  ASSERT_EQ(ruled.status, SolveStatus::kOptimal);
  EXPECT_NEAR(ruled.objective, plain.objective, 1e-4 * std::max(1.0, std::abs(plain.objective)));
  // Long after 4 nodes: the first pass's 4 nodes, then the loop and the search with cuts.
  BranchAndBoundOptions after = at_root;
  after.long_search_min_nodes = 4;
  const BranchAndBoundResult restarted = Solve(after);
  ASSERT_EQ(restarted.status, SolveStatus::kOptimal);
  EXPECT_NEAR(restarted.objective, plain.objective, 1e-4 * std::max(1.0, std::abs(plain.objective)));
  EXPECT_GE(restarted.nodes, 4);
}

}  // namespace
}  // namespace mfp
