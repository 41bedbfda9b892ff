#include "planner/planning/internal/window_budget.h"

#include <algorithm>

#include "base/check.h"

namespace mfp {

double EstimatedWindowsLeft(const WindowBudgetInput& in) {
  MFP_CHECK(in.prior_advance_m > 0.0 && in.accepted_windows >= 0);
  const double advance = (in.prior_advance_m + std::max(0.0, in.route_covered_m)) / (1.0 + in.accepted_windows);
  // A window that advanced nothing (a stall, a retry) is still a window: never below a
  // tenth of the prior, so the estimate stays finite.
  return std::max(1.0, std::max(0.0, in.route_left_m) / std::max(advance, 0.1 * in.prior_advance_m));
}

double WindowTimeShare(const WindowBudgetInput& in) {
  MFP_CHECK(in.slack > 0.0);
  const double remaining = std::max(0.0, in.remaining_s);
  return std::min(0.5 * remaining, in.slack * remaining / EstimatedWindowsLeft(in));
}

}  // namespace mfp
