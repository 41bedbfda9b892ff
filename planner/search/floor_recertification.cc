#include "planner/search/internal/floor_recertification.h"

#include <algorithm>
#include <vector>

#include "planner/search/internal/bound_propagation.h"

namespace mfp {
namespace {

// The kept subtree of the least floor, or null when none is kept.
SettledSubtree* Lowest(std::vector<SettledSubtree>* kept) {
  auto it = std::min_element(kept->begin(), kept->end(),
                             [](const SettledSubtree& a, const SettledSubtree& b) { return a.floor < b.floor; });
  return it == kept->end() ? nullptr : &*it;
}

// One exact solve of `subtree`'s relaxation; returns the floor it certifies (+infinity
// when the subtree's box holds no feasible point, its own floor when the solve certifies
// nothing more).
double CertifiedFloorOf(SearchState* state, const SettledSubtree& subtree) {
  const Miqp& p = state->problem();
  Eigen::VectorXd lower = subtree.lower, upper = subtree.upper;
  if (!subtree.propagated && state->options().bound_propagation && PropagateBounds(p, &lower, &upper).infeasible) {
    return kInfinity;
  }
  const Eigen::VectorXd* warm = subtree.relaxed.size() ? &subtree.relaxed : nullptr;
  // The cutoff at the floor a proof needs: a solve may stop once it certifies that much.
  RelaxationRequest request = state->Request(std::move(lower), std::move(upper), warm, state->ProofFloor());
  request.certify_floor = true;
  const RelaxationResult r = state->solver(0).Solve(p, request);
  BranchAndBoundResult& result = state->result();
  ++result.relaxations;
  ++result.floor_recertifications;
  CountFallbacks(r, &result);
  if (r.status == RelaxationStatus::kInfeasible) return kInfinity;
  if (r.status == RelaxationStatus::kCutoff) return std::max(subtree.floor, r.objective);  // its objective is a floor
  if (r.status == RelaxationStatus::kSolved) return std::max(subtree.floor, r.CertifiedFloor());
  return subtree.floor;
}

}  // namespace

void RecertifyLaggingFloors(SearchState* state) {
  LaggingFloors& lagging = state->lagging();
  const double target = state->ProofFloor();
  // A subtree not kept misses the proof already: solving the kept ones cannot give it.
  if (!(lagging.rest_floor() >= target)) return;
  while (!state->Active().Expired()) {
    SettledSubtree* lowest = Lowest(&lagging.kept());
    if (lowest == nullptr || lowest->floor >= target || lowest->recertified) break;
    lowest->floor = CertifiedFloorOf(state, *lowest);
    lowest->recertified = true;
    if (lowest->floor >= target) ++state->result().floors_certified;
  }
  state->RaiseGapPrunedBound();
}

}  // namespace mfp
