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

}  // namespace mfp
