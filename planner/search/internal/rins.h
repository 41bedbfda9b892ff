#pragma once
// An improvement heuristic on the incumbent: relaxation induced neighbourhood search
// (RINS, Danna, Rothberg and Le Pape 2005). The integers on which the incumbent and a
// node's relaxation agree are fixed to the incumbent's values and the smaller MIQP left
// is searched by a branch-and-bound of its own, capped in nodes and under the search's
// deadline, started from the incumbent; a better plan it finds is offered as the
// incumbent. BranchAndBoundOptions::rins_frequency and the options beside it.
#include <Eigen/Core>

#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/search_state.h"

namespace mfp {

struct RinsOutcome {
  bool ran = false;  // false: no incumbent, time is up, or too few or all integers agree
  bool improved = false;
  int fixed = 0;  // integers fixed to the incumbent's values
  int nodes = 0;  // of the sub-search
};

// relaxed: a node's relaxation point; proposals: the search's rounding proposals, also
// offered to the sub-search (with the incumbent itself).
RinsOutcome RunRins(SearchState* state, const Eigen::VectorXd& relaxed, const RoundingHeuristic& proposals);

// When the search runs RINS: at the root (after its heuristics) when rins_after_nodes is 0;
// at a branched node, first once the plan has not improved for rins_after_nodes nodes, then
// each time the interval has passed since the last run; always only while the search
// holds a plan whose gap to the bound exceeds rins_min_gap. The interval starts at
// rins_frequency, is multiplied by rins_backoff after each run that did not improve the
// plan by more than the search's gap tolerance, and returns to rins_frequency after one
// that did. It counts nodes and reads gaps, no clock (SearchState::IsLong, which the search
// also asks before a run, does).
class RinsSchedule {
 public:
  explicit RinsSchedule(const BranchAndBoundOptions& options)
      : options_(options), interval_(options.rins_frequency) {}

  bool DueAtRoot(const SearchState& state) const {
    return options_.rins_frequency > 0 && options_.rins_after_nodes <= 0 && GapCalls(state);
  }
  bool DueAtNode(const SearchState& state) const {
    const bool started = last_node_ > 0 || state.NodesSinceImprovement() >= options_.rins_after_nodes;
    return options_.rins_frequency > 0 && started && state.result().nodes - last_node_ >= interval_ &&
           GapCalls(state);
  }
  // A run has been tried at the search's current node; objective_before: the incumbent's
  // objective when it started.
  void Record(const SearchState& state, const RinsOutcome& outcome, double objective_before);

 private:
  bool GapCalls(const SearchState& state) const;

  const BranchAndBoundOptions& options_;
  double interval_;  // [nodes]
  int last_node_ = 0;
};

}  // namespace mfp
