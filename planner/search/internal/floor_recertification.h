#pragma once
// Re-certification of a search's lagging floors (BranchAndBoundOptions::recertify_leaves):
// once its tree is exhausted short of the gap asked, the kept subtrees (LaggingFloors) of
// the lowest floors are solved again with RelaxationRequest::certify_floor, lowest first,
// and their floors raised to what those solves certify. A floor only rises to a solve's
// certified floor of the subtree's own relaxation, which is never above the subtree's
// optimum.
#include "planner/search/internal/search_state.h"

namespace mfp {

// Solves kept subtrees again on the first worker's solver while the least floor of the
// settled subtrees misses state->ProofFloor(), the least is a kept subtree not yet solved
// again, and the deadline in force has not passed; then raises the search's gap-pruned
// bound to the least floor. Counts its solves in the result (relaxations,
// floor_recertifications, floors_certified).
void RecertifyLaggingFloors(SearchState* state);

}  // namespace mfp
