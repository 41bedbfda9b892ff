#include "planner/search/internal/floor_recertification.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "base/check.h"
#include "planner/search/internal/bound_propagation.h"

namespace mfp {
namespace {

// The kept subtree of the least floor, or end() when none is kept.
std::vector<SettledSubtree>::iterator Lowest(std::vector<SettledSubtree>* kept) {
  return std::min_element(kept->begin(), kept->end(),
                          [](const SettledSubtree& a, const SettledSubtree& b) { return a.floor < b.floor; });
}

// One exact solve of `subtree`'s relaxation (its box propagated first when it was not);
// an empty box is reported kInfeasible without a solve.
RelaxationResult CertifyingSolve(SearchState* state, SettledSubtree* subtree) {
  const Miqp& p = state->problem();
  if (!subtree->propagated && state->options().bound_propagation &&
      PropagateBounds(p, &subtree->lower, &subtree->upper).infeasible) {
    RelaxationResult empty;
    empty.status = RelaxationStatus::kInfeasible;
    return empty;
  }
  subtree->propagated = true;
  const Eigen::VectorXd* warm = subtree->relaxed.size() ? &subtree->relaxed : nullptr;
  // The cutoff at the floor a proof needs: a solve may stop once it certifies that much.
  RelaxationRequest request = state->Request(subtree->lower, subtree->upper, warm, state->ProofFloor());
  request.certify_floor = true;
  RelaxationResult r = state->solver(0).Solve(p, request);
  BranchAndBoundResult& result = state->result();
  ++result.relaxations;
  ++result.floor_recertifications;
  CountFallbacks(r, &result);
  return r;
}

// The floor a certifying solve proves of its subtree, never below the subtree's own.
double FloorAfter(const SettledSubtree& subtree, const RelaxationResult& r) {
  if (r.status == RelaxationStatus::kInfeasible) return kInfinity;
  if (r.status == RelaxationStatus::kCutoff) return std::max(subtree.floor, r.objective);  // its objective is a floor
  if (r.status == RelaxationStatus::kSolved) return std::max(subtree.floor, r.CertifiedFloor());
  return subtree.floor;
}

// options.recertify_within, once per search, before the first solve: its ranges become
// the search's restriction and cut every kept subtree's box (to be propagated again); a
// box they leave empty holds nothing of the restricted problem (floor +infinity). Ranges
// the incumbent does not meet restrict nothing.
void RestrictToWhatTheIncumbentKeeps(SearchState* state) {
  const BranchAndBoundOptions& options = state->options();
  if (!options.recertify_within || !state->FirstRestrictionAsk()) return;
  const std::vector<VariableRange> ranges = options.recertify_within(state->result().x);
  if (ranges.empty()) return;
  const Miqp& p = state->problem();
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  for (const VariableRange& r : ranges) {
    MFP_CHECK(r.index >= 0 && r.index < p.num_variables());
    lower(r.index) = std::max(lower(r.index), r.lower);
    upper(r.index) = std::min(upper(r.index), r.upper);
  }
  if (!state->Within(state->result().x, lower, upper)) return;
  for (SettledSubtree& subtree : state->lagging().kept()) {
    subtree.lower = subtree.lower.cwiseMax(lower);
    subtree.upper = subtree.upper.cwiseMin(upper);
    subtree.propagated = false;
    if ((subtree.lower.array() > subtree.upper.array()).any()) subtree.floor = kInfinity;
  }
  state->Restrict(std::move(lower), std::move(upper));
}

}  // namespace

std::optional<ReopenedSubtree> RecertifyLaggingFloors(SearchState* state) {
  LaggingFloors& lagging = state->lagging();
  BranchAndBoundResult& result = state->result();
  const double target = state->ProofFloor();
  // A subtree not kept misses the proof already: solving the kept ones cannot give it.
  if (!(lagging.rest_floor() >= target)) return std::nullopt;
  RestrictToWhatTheIncumbentKeeps(state);
  std::vector<SettledSubtree>& kept = lagging.kept();
  while (!state->Active().Expired() && result.floor_recertifications < state->options().recertify_leaves) {
    auto lowest = Lowest(&kept);
    if (lowest == kept.end() || lowest->floor >= target || lowest->recertified) break;
    RelaxationResult r = CertifyingSolve(state, &*lowest);
    if (r.status == RelaxationStatus::kSolved && state->Improves(r.objective)) {
      ReopenedSubtree reopened{std::move(*lowest), std::move(r)};
      kept.erase(lowest);
      return reopened;
    }
    lowest->floor = FloorAfter(*lowest, r);
    lowest->recertified = true;
    if (lowest->floor >= target) ++result.floors_certified;
  }
  state->RaiseGapPrunedBound();
  return std::nullopt;
}

}  // namespace mfp
