#include "planner/search/internal/search_heuristics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "planner/qp/fixed_integer_qp.h"
#include "planner/search/internal/bound_propagation.h"
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

// True when bound propagation with the proposal's integers fixed proves that no point
// completes it: its QP would end infeasible, and an interior point takes many iterations
// to say so (docs/measurements.md). The tolerance is the incumbent's, so a proposal whose
// QP could end within it is never skipped.
bool ProvenIncomplete(const SearchState& state, const Eigen::VectorXd& proposal) {
  const Miqp& p = state.problem();
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (p.is_integer[j]) lower(j) = upper(j) = std::clamp(std::round(proposal(j)), p.var_lower(j), p.var_upper(j));
  }
  return PropagateBounds(p, &lower, &upper, 3, state.options().feasibility_tolerance).infeasible;
}

// A completion QP that cannot end below the incumbent cannot become the incumbent: its
// solve may stop once it proves that (RelaxationRequest::cutoff). The cutoff lies a hair
// above the incumbent, by kCompletionCutoffMargin times max(1, |incumbent|): far below
// any search's gap (relative_gap, 1e-4 by default), so it never decides which plan a
// search keeps, yet above the solvers' round-off, so that a completion ending within the
// solver's feasibility tolerance below the incumbent is still solved to the end and
// offered as before. A numerical margin of the algorithm, not a setting.
constexpr double kCompletionCutoffMargin = 1e-6;

double CompletionCutoff(const SearchState& state) {
  if (!state.HasIncumbent()) return kInfinity;
  const double incumbent = state.result().objective;
  return incumbent + kCompletionCutoffMargin * std::max(1.0, std::abs(incumbent));
}

// Each proposal offered as it is (a heuristic's own plan is kept even when no time is
// left for its QP), then completed: its integers fixed and the QP left solved, a round
// of workers at a time, warm-started from the relaxation point x. With bound propagation
// on, proposals that propagation proves incomplete get no QP; with
// rounding_stops_at_first_plan, no QP is started once the search holds a plan. The QPs
// run under SearchState::RoundingDeadline: past the deadline only until the first plan.
void OfferAndComplete(SearchState* state, const std::vector<Eigen::VectorXd>& all, const Eigen::VectorXd& x) {
  const Miqp& p = state->problem();
  for (const Eigen::VectorXd& proposal : all) state->OfferIncumbent(proposal);
  std::vector<Eigen::VectorXd> proposals;
  for (const Eigen::VectorXd& proposal : all) {
    if (!state->options().bound_propagation || !ProvenIncomplete(*state, proposal)) proposals.push_back(proposal);
  }
  const int workers = state->workers();
  for (size_t first = 0; first < proposals.size(); first += workers) {
    const Deadline deadline = state->RoundingDeadline();
    if (deadline.Expired()) return;
    if (state->options().rounding_stops_at_first_plan && state->HasIncumbent()) return;
    const int count = static_cast<int>(std::min<size_t>(workers, proposals.size() - first));
    std::vector<RelaxationResult> results(count);
    RelaxationRequest request = state->Request(Eigen::VectorXd(), Eigen::VectorXd(), &x, CompletionCutoff(*state));
    request.deadline = deadline;
    ForEachInParallel(count, [&](int k) {
      results[k] = SolveWithIntegersFixed(p, proposals[first + k], state->solver(k), request);
    });
    state->result().relaxations += count;
    for (RelaxationResult& rel : results) {
      CountFallbacks(rel, &state->result());
      if (rel.status == RelaxationStatus::kSolved) state->OfferIncumbent(std::move(rel.x));
    }
  }
}

}  // namespace

void TryRounding(SearchState* state, const Branching& branching, const RoundingHeuristic& proposals_of,
                 const Eigen::VectorXd& x) {
  if (!state->options().rounding_heuristic) return;
  std::vector<Eigen::VectorXd> proposals;
  if (proposals_of) proposals = proposals_of(x);
  proposals.push_back(SimpleRounding(state->problem(), branching, x));
  OfferAndComplete(state, proposals, x);
}

bool RunRootHeuristic(SearchState* state, const Eigen::VectorXd& x) {
  const BranchAndBoundOptions& options = state->options();
  if (!options.rounding_heuristic) return false;
  if (options.first_plan_heuristic && !state->HasIncumbent()) {
    OfferAndComplete(state, options.first_plan_heuristic(x), x);
  }
  if (!options.root_heuristic) return false;
  // Wait only where the search can reach the node count at all (max_nodes) and in time.
  if (options.root_heuristic_after_nodes > 0 && options.max_nodes > options.root_heuristic_after_nodes &&
      state->HasIncumbent() &&
      RelativeGap(state->result().objective, state->result().bound) <= options.root_heuristic_wait_gap &&
      state->TimeHoldsNodes(options.root_heuristic_after_nodes)) {
    return true;
  }
  OfferAndComplete(state, options.root_heuristic(x), x);
  return false;
}

void RunDeferredRootHeuristic(SearchState* state, const Eigen::VectorXd& root_x) {
  OfferAndComplete(state, state->options().root_heuristic(root_x), root_x);
}

}  // namespace mfp
