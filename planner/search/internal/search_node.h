#pragma once
// A branch-and-bound node: its parent's bound plus the bound changes from the root, and
// the branching that made it (for the pseudo-costs).
#include <Eigen/Core>
#include <vector>

#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

struct BoundChange {
  int index;
  double lower, upper;
};

struct SearchNode {
  std::vector<BoundChange> changes;
  // What orders and prunes the node: its parent's relaxation objective (at least its
  // ancestors'). An interior point's objective may lie above what its solve certifies.
  double parent_bound = -kInfinity;
  // What the subtree's bound is claimed to be: its parent's certified floor
  // (RelaxationResult::CertifiedFloor, at least its ancestors').
  double parent_floor = -kInfinity;
  int depth = 0;
  // The branching that made this node, for the pseudo-costs.
  int branch_var = -1;
  bool branch_up = false;
  double branch_distance = 0.0;
  double parent_objective = 0.0;
  Eigen::VectorXd warm_start;  // parent's relaxation point
  // The parent's solver hint (RelaxationResult::warm_token), shared by both children; at
  // most one int per variable, so no more than warm_start's size.
  WarmStartToken warm_token;
};

}  // namespace mfp
