#include "planner/search/internal/reduced_cost_fixing.h"

#include <cmath>

namespace mfp {

void FixByReducedCosts(const RelaxationResult& rel, SearchState* state, Eigen::VectorXd* lower,
                       Eigen::VectorXd* upper, std::vector<BoundChange>* fixings) {
  const Miqp& p = state->problem();
  const double integrality_tolerance = state->options().integrality_tolerance;
  if (rel.lower_cost_rate.size() != p.num_variables() || !std::isfinite(rel.cost_floor)) return;
  // The objective increase still allowed.
  const double room = state->result().objective - state->GapTolerance() - rel.cost_floor;
  if (room < 0.0) return;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (!p.is_integer[j] || (*lower)(j) >= (*upper)(j)) continue;
    double lo = (*lower)(j), hi = (*upper)(j);
    const double up_rate = rel.lower_cost_rate(j), down_rate = rel.upper_cost_rate(j);
    if (up_rate > 0.0 && lo + room / up_rate < hi) {
      const double new_hi = std::floor(lo + room / up_rate + integrality_tolerance);
      if (new_hi < hi) {
        state->NoteGapPrune(rel.cost_floor + up_rate * (new_hi + 1.0 - lo));
        hi = new_hi;
      }
    }
    if (down_rate > 0.0 && hi - room / down_rate > lo) {
      const double new_lo = std::ceil(hi - room / down_rate - integrality_tolerance);
      if (new_lo > lo) {
        state->NoteGapPrune(rel.cost_floor + down_rate * ((*upper)(j) - (new_lo - 1.0)));
        lo = new_lo;
      }
    }
    if (lo == (*lower)(j) && hi == (*upper)(j)) continue;
    ++state->result().reduced_cost_fixings;
    fixings->push_back({j, lo, hi});
    (*lower)(j) = lo;
    (*upper)(j) = hi;
  }
}

}  // namespace mfp
