#include "planner/search/internal/rins.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mfp {
namespace {

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

}  // namespace mfp
