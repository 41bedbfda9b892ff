#pragma once
// Re-certification of a search's lagging floors (BranchAndBoundOptions::recertify_leaves):
// once its tree is exhausted short of the gap asked, the kept subtrees (LaggingFloors) of
// the lowest floors are solved again with RelaxationRequest::certify_floor, lowest first,
// and their floors raised to what those solves certify. A floor only rises to a solve's
// certified floor of the subtree's own relaxation, which is never above the subtree's
// optimum. A subtree whose solve shows that it may still beat the incumbent by more than
// the gap (it was pruned by an objective its interior point put too high) is handed back
// to the search, to be branched on from that solve. Before its first solve the search may
// be restricted to what the incumbent keeps (BranchAndBoundOptions::recertify_within).
#include <optional>

#include "planner/search/internal/search_state.h"

namespace mfp {

struct ReopenedSubtree {
  SettledSubtree subtree;         // its box propagated
  RelaxationResult relaxation;    // the certifying solve, kSolved
};

// Solves kept subtrees again on the first worker's solver while the least floor of the
// settled subtrees misses state->ProofFloor(), the least is a kept subtree not yet solved
// again, the search's solves of this kind stay within options.recertify_leaves, and the
// deadline in force has not passed; before the first solve the kept subtrees are cut to
// the ranges of options.recertify_within (once per search). Returns the first subtree
// whose solve improves on the incumbent by more than the gap (SearchState::Improves), taken out of the store:
// the caller searches it, which settles its floor again. Otherwise raises the search's
// gap-pruned bound to the least floor and returns nothing. Counts its solves in the
// result (relaxations, floor_recertifications, floors_certified).
std::optional<ReopenedSubtree> RecertifyLaggingFloors(SearchState* state);

}  // namespace mfp
