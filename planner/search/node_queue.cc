#include "planner/search/internal/node_queue.h"

#include <algorithm>
#include <cmath>

namespace mfp {

void NodeQueue::PushChildren(std::vector<SearchNode> children) {
  just_branched_ = !children.empty();
  for (SearchNode& child : children) open_.push_back(std::move(child));
}

SearchNode NodeQueue::Pop(bool has_incumbent, double incumbent_objective) {
  size_t pick = open_.size() - 1;  // depth first: newest
  const bool plunge = just_branched_ && PlungeContinues(open_.back().parent_bound, has_incumbent, incumbent_objective);
  just_branched_ = false;
  const bool best_bound = selection_ == NodeSelection::kBestBound ||
                          (selection_ == NodeSelection::kDiveThenBestBound && has_incumbent) ||
                          (selection_ == NodeSelection::kBestBoundWithPlunging && !plunge);
  if (best_bound) {
    for (size_t k = 0; k < open_.size(); ++k) {
      const SearchNode& a = open_[k];
      const SearchNode& b = open_[pick];
      if (a.parent_bound < b.parent_bound - 1e-12 ||
          (std::abs(a.parent_bound - b.parent_bound) <= 1e-12 && a.depth > b.depth)) {
        pick = k;
      }
    }
  }
  SearchNode node = std::move(open_[pick]);
  open_[pick] = std::move(open_.back());
  open_.pop_back();
  return node;
}

double NodeQueue::LeastBound() const {
  double bound = kInfinity;
  for (const SearchNode& node : open_) bound = std::min(bound, node.parent_bound);
  return bound;
}

double NodeQueue::LeastFloor() const {
  double floor = kInfinity;
  for (const SearchNode& node : open_) floor = std::min(floor, node.parent_floor);
  return floor;
}

bool NodeQueue::PlungeContinues(double child_bound, bool has_incumbent, double incumbent_objective) const {
  if (selection_ != NodeSelection::kBestBoundWithPlunging) return false;
  if (!has_incumbent) return true;
  const double best = std::min(child_bound, LeastBound());
  return child_bound <= best + plunge_fraction_ * (incumbent_objective - best);
}

}  // namespace mfp
