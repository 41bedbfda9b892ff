#pragma once
// How much of a plan's remaining time one receding window's search may take. Under route
// guidance the number of windows still needed is estimated from the route left and the
// route covered per window so far, so no early window spends on proving optimality the
// time later windows need to reach the goal. No I/O.

namespace mfp {

struct WindowBudgetInput {
  double remaining_s = 0.0;           // the plan's time left
  double route_left_m = 0.0;          // route from the stance's progress to the goal
  double route_covered_m = 0.0;       // route covered by the accepted windows so far
  int accepted_windows = 0;           // windows whose steps were kept
  double prior_advance_m = 0.0;       // a window's advance before any was measured
  double slack = 2.0;                 // share multiplier: a window may take this many fair shares
};

// Estimated windows left: the route left over the measured advance per window (the prior
// counts as one window, so one slow window does not swing the estimate); at least 1.
double EstimatedWindowsLeft(const WindowBudgetInput& in);

// The window's search time [s]: slack fair shares of the remaining time, and never more
// than half of it (the retries and the polisher need some).
double WindowTimeShare(const WindowBudgetInput& in);

}  // namespace mfp
