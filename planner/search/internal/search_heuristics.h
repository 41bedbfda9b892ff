#pragma once
// The branch-and-bound's primal heuristic (BranchAndBoundOptions::rounding_heuristic):
// at the root, and every rounding_frequency nodes of a dive, the relaxation point is
// rounded (the caller's proposals, such as the plan-ordered roundings and relax-and-fix's
// plan, then one simple rounding) and each rounding's integers are fixed and the QP left
// solved; every plan found is offered as the incumbent.
#include <Eigen/Core>

#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/branching.h"
#include "planner/search/internal/search_state.h"

namespace mfp {

void TryRounding(SearchState* state, const Branching& branching, const RoundingHeuristic& proposals,
                 const Eigen::VectorXd& x);

// BranchAndBoundOptions::first_plan_heuristic (only while the search has no incumbent),
// then root_heuristic, on the root relaxation point x, their proposals offered and
// completed as TryRounding's. Nothing when rounding_heuristic is off. Returns true when
// root_heuristic was left for later (root_heuristic_after_nodes > 0, the search holds a
// plan within root_heuristic_wait_gap of the root bound, state->result().bound, and its
// time left holds that many nodes at its pace so far): the caller runs it by
// RunDeferredRootHeuristic once the nodes are processed.
bool RunRootHeuristic(SearchState* state, const Eigen::VectorXd& x);

// root_heuristic on the root relaxation point root_x, its proposals offered and completed
// (warm-started from root_x), as RunRootHeuristic would have at the root.
void RunDeferredRootHeuristic(SearchState* state, const Eigen::VectorXd& root_x);

}  // namespace mfp
