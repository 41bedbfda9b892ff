#include "planner/search/internal/rins.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mfp {
namespace {

// The back-off's largest interval [nodes]: beyond any node limit (search.max_nodes is at
// most 1e7); it only keeps the product finite.
constexpr double kMaxInterval = 1e9;

// The sub-search: the search's own options, but none of its once-per-plan heuristics, no
// root cut loop, no RINS of its own, no re-certification, and the node cap and the deadline in force.
BranchAndBoundOptions SubSearchOptions(const SearchState& state) {
  BranchAndBoundOptions sub = state.options();
  sub.max_nodes = std::max(1, sub.rins_max_nodes);
  sub.deadline = state.Active();
  sub.time_limit_needs_incumbent = false;
  sub.first_plan_overrun_s = 0.0;  // the search it serves holds a plan
  sub.stall_time_fraction = 0.0;
  sub.rins_frequency = 0;
  sub.root_cut_rounds = 0;
  sub.recertify_leaves = 0;  // its bound is not the search's
  sub.root_heuristic = nullptr;
  sub.first_plan_heuristic = nullptr;
  sub.on_incumbent = nullptr;
  sub.node_selection = sub.rins_node_selection;
  return sub;
}

}  // namespace

RinsOutcome RunRins(SearchState* state, const Eigen::VectorXd& relaxed, const RoundingHeuristic& proposals) {
  RinsOutcome outcome;
  const Miqp& p = state->problem();
  const BranchAndBoundOptions& options = state->options();
  if (!state->HasIncumbent() || state->Active().Expired()) return outcome;
  const Eigen::VectorXd incumbent = state->result().x;
  const double incumbent_objective = state->result().objective;
  Miqp sub = p;
  int integers = 0;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (!p.is_integer[j]) continue;
    ++integers;
    if (std::abs(relaxed(j) - incumbent(j)) <= options.rins_agreement) {
      sub.var_lower(j) = sub.var_upper(j) = std::round(incumbent(j));
      ++outcome.fixed;
    }
  }
  if (outcome.fixed == integers || outcome.fixed < options.rins_min_fixed_fraction * integers) return outcome;
  outcome.ran = true;
  std::vector<RelaxationSolver*> solvers;
  for (int k = 0; k < state->workers(); ++k) solvers.push_back(&state->solver(k));
  const RoundingHeuristic with_incumbent = [&](const Eigen::VectorXd& x) {
    std::vector<Eigen::VectorXd> all{incumbent};
    if (proposals) {
      for (Eigen::VectorXd& proposal : proposals(x)) all.push_back(std::move(proposal));
    }
    return all;
  };
  const BranchAndBoundOptions sub_options = SubSearchOptions(*state);
  const BranchAndBoundResult found = SolveBranchAndBound(sub, solvers, sub_options, with_incumbent);
  outcome.nodes = found.nodes;
  state->result().relaxations += found.relaxations;
  state->result().fallbacks += found.fallbacks;
  state->result().fallback_time_s += found.fallback_time_s;
  if (found.x.size() > 0 && found.objective < incumbent_objective) {
    state->OfferIncumbent(found.x);
    outcome.improved = state->result().objective < incumbent_objective;
  }
  return outcome;
}

void RinsSchedule::Record(const SearchState& state, const RinsOutcome& outcome, double objective_before) {
  last_node_ = state.result().nodes;
  if (!outcome.ran) return;
  const bool improved = objective_before - state.result().objective > state.GapTolerance();
  interval_ = improved ? options_.rins_frequency : std::min(interval_ * options_.rins_backoff, kMaxInterval);
}

bool RinsSchedule::GapCalls(const SearchState& state) const {
  if (!state.HasIncumbent()) return false;
  return RelativeGap(state.result().objective, state.BoundNow()) > options_.rins_min_gap;
}

}  // namespace mfp
