#pragma once
// Reduced-cost fixing (BranchAndBoundOptions::reduced_cost_fixing): integer values whose
// subtree cannot beat the incumbent by more than the gap, by the relaxation's reduced-cost
// certificate (RelaxationResult::cost_floor and rates): x_j >= l_j + t costs at least
// floor + rate_l t (likewise below u_j).
#include <Eigen/Core>
#include <vector>

#include "planner/qp/relaxation_solver.h"
#include "planner/search/internal/search_node.h"
#include "planner/search/internal/search_state.h"

namespace mfp {

// Tightens lower/upper (the node's bounds, which both children inherit) and appends the
// changes to fixings; the bound of what they rule out is noted in state for the final
// gap. Needs an incumbent.
void FixByReducedCosts(const RelaxationResult& rel, SearchState* state, Eigen::VectorXd* lower,
                       Eigen::VectorXd* upper, std::vector<BoundChange>* fixings);

}  // namespace mfp
