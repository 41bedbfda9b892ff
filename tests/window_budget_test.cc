// A window's share of the plan's time under route guidance (planner/planning/internal/window_budget.h).
#include "planner/planning/internal/window_budget.h"

#include <gtest/gtest.h>

namespace mfp {
namespace {

WindowBudgetInput Input() {
  WindowBudgetInput in;
  in.remaining_s = 6.0;
  in.route_left_m = 2.0;
  in.prior_advance_m = 0.2;
  in.slack = 1.0;
  return in;
}

TEST(WindowBudget, BeforeAnyWindowTheRouteOverThePriorAdvanceSetsTheShare) {
  // 2 m of route at 0.2 m per window: 10 windows, one fair share = 0.6 s.
  const WindowBudgetInput in = Input();
  EXPECT_NEAR(EstimatedWindowsLeft(in), 10.0, 1e-12);
  EXPECT_NEAR(WindowTimeShare(in), 0.6, 1e-12);
}

TEST(WindowBudget, MeasuredAdvanceReplacesThePrior) {
  // Three windows covered 0.3 m (0.1 m each); with the prior as a fourth window the
  // advance is (0.2 + 0.3) / 4 = 0.125 m: 16 windows left, 0.375 s each, twice that
  // with a slack of 2.
  WindowBudgetInput in = Input();
  in.accepted_windows = 3;
  in.route_covered_m = 0.3;
  EXPECT_NEAR(EstimatedWindowsLeft(in), 16.0, 1e-12);
  in.slack = 2.0;
  EXPECT_NEAR(WindowTimeShare(in), 0.75, 1e-12);
}

TEST(WindowBudget, NeverMoreThanHalfTheRemainingTimeAndAlwaysOneWindowLeft) {
  WindowBudgetInput in = Input();
  in.route_left_m = 0.05;  // less than one window: still one window
  EXPECT_NEAR(EstimatedWindowsLeft(in), 1.0, 1e-12);
  EXPECT_NEAR(WindowTimeShare(in), 3.0, 1e-12);
  // Windows that went nowhere (route covered 0, or backwards after a retry) keep the
  // estimate finite: the advance never drops below a tenth of the prior.
  in.route_left_m = 2.0;
  in.accepted_windows = 20;
  in.route_covered_m = -0.5;
  EXPECT_NEAR(EstimatedWindowsLeft(in), 100.0, 1e-12);
  EXPECT_NEAR(WindowTimeShare(in), 0.06, 1e-12);
}

}  // namespace
}  // namespace mfp
