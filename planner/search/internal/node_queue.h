#pragma once
// The open nodes of a branch-and-bound and the node selection rule
// (BranchAndBoundOptions::node_selection): which open node the search takes next.
#include <vector>

#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/search_node.h"

namespace mfp {

class NodeQueue {
 public:
  NodeQueue(NodeSelection selection, double plunge_fraction)
      : selection_(selection), plunge_fraction_(plunge_fraction) {}

  bool empty() const { return open_.empty(); }
  const std::vector<SearchNode>& nodes() const { return open_; }

  void Push(SearchNode node) { open_.push_back(std::move(node)); }
  // The children of a branching, in the order given: the last is the preferred child,
  // the one a dive or a plunge goes on with.
  void PushChildren(std::vector<SearchNode> children);

  // Takes the next node to explore (the queue must not be empty). The incumbent's
  // objective (has_incumbent false: none yet) decides between diving and best bound.
  SearchNode Pop(bool has_incumbent, double incumbent_objective);

  // The least parent bound of the open nodes (+infinity when none).
  double LeastBound() const;
  // The least certified parent floor of the open nodes (+infinity when none).
  double LeastFloor() const;

 private:
  // Plunging: the newest node is the child just pushed; go on with it while its bound is
  // close enough to the best open bound, measured against the incumbent.
  bool PlungeContinues(double child_bound, bool has_incumbent, double incumbent_objective) const;

  const NodeSelection selection_;
  const double plunge_fraction_;
  std::vector<SearchNode> open_;
  bool just_branched_ = false;  // open_.back() is the preferred child of the last branching
};

}  // namespace mfp
