#pragma once
// Reliability branching (BranchingRule::kReliability): candidates scored by their
// pseudo-costs; those whose pseudo-costs are not yet reliable are strong-branched (both
// children's relaxations solved, side by side with two workers) and their trials teach
// the pseudo-costs.
#include <Eigen/Core>

#include "planner/qp/relaxation_solver.h"
#include "planner/search/internal/branching.h"
#include "planner/search/internal/pseudo_costs.h"
#include "planner/search/internal/search_state.h"

namespace mfp {

class ReliabilityBranching {
 public:
  ReliabilityBranching(SearchState* state, const Branching* branching, PseudoCosts* pseudo)
      : state_(*state), branching_(*branching), pseudo_(*pseudo) {}

  // The variable to branch on at the node's relaxation rel within lower/upper, -1 when
  // rel.x is integral, or kPruned when strong branching shows that both children of
  // some candidate are empty or cut off.
  int Choose(const RelaxationResult& rel, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

 private:
  // gain[down, up]: each child's objective increase over its parent (see RecordTrial).
  void StrongBranchGains(int j, const Eigen::VectorXd& x, double parent_objective, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper, double gain[2]);
  // The objective increase of one strong-branching child over its parent, +inf when the
  // child is empty or cannot beat the incumbent; recorded in the pseudo-costs when solved.
  double RecordTrial(int j, bool up, double parent_objective, double distance, bool empty,
                     const RelaxationResult& child);

  SearchState& state_;
  const Branching& branching_;
  PseudoCosts& pseudo_;
};

}  // namespace mfp
