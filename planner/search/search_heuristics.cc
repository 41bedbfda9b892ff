#include "planner/search/internal/search_heuristics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "planner/qp/fixed_integer_qp.h"
#include "planner/search/internal/parallel_for.h"

namespace mfp {
namespace {

// Each one-of group's largest member set to 1 and the others to 0; other integers rounded.
Eigen::VectorXd SimpleRounding(const Miqp& p, const Branching& branching, const Eigen::VectorXd& x) {
  Eigen::VectorXd simple = x;
  for (const auto& group : p.sos1_groups) {
    int top = group.front();
    for (int j : group) {
      if (x(j) > x(top)) top = j;
    }
    for (int j : group) simple(j) = j == top ? 1.0 : 0.0;
  }
  for (int j = 0; j < p.num_variables(); ++j) {
    if (p.is_integer[j] && branching.GroupOf(j) < 0) simple(j) = std::round(x(j));
  }
  return simple;
}

}  // namespace

void TryRounding(SearchState* state, const Branching& branching, const RoundingHeuristic& proposals_of,
                 const Eigen::VectorXd& x) {
  if (!state->options().rounding_heuristic) return;
  const Miqp& p = state->problem();
  std::vector<Eigen::VectorXd> proposals;
  if (proposals_of) proposals = proposals_of(x);
  proposals.push_back(SimpleRounding(p, branching, x));
  // A proposal may already be a plan (a heuristic's own, such as relax-and-fix's): it
  // is kept even when no time is left for its QP.
  for (const Eigen::VectorXd& proposal : proposals) state->OfferIncumbent(proposal);
  // Each proposal is a QP with the integers fixed: solved a round of workers at a time.
  const int workers = state->workers();
  for (size_t first = 0; first < proposals.size(); first += workers) {
    if (state->Active().Expired()) return;
    const int count = static_cast<int>(std::min<size_t>(workers, proposals.size() - first));
    std::vector<RelaxationResult> results(count);
    const RelaxationRequest request = state->Request(Eigen::VectorXd(), Eigen::VectorXd(), &x);
    ForEachInParallel(count, [&](int k) {
      results[k] = SolveWithIntegersFixed(p, proposals[first + k], state->solver(k), request);
    });
    state->result().relaxations += count;
    for (RelaxationResult& rel : results) {
      if (rel.status == RelaxationStatus::kSolved) state->OfferIncumbent(std::move(rel.x));
    }
  }
}

}  // namespace mfp
