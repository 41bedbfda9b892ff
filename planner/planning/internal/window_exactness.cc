#include "planner/planning/internal/window_exactness.h"

#include <algorithm>
#include <utility>

namespace mfp {

ExactWindow MakeWindowExact(const PlanContext& context, const MiqpFormulation& formulation, WindowSearch search,
                            bool first_plan) {
  // The polisher's time comes out of the plan's: at most what is left of it. A window
  // whose plan would be the plan's first has nothing else to return: its polisher may run
  // until polish.completion_overrun_s past the plan's limit (counted from that limit, so
  // with the first plan's work, which may overrun by the same, nothing ends later than
  // limit + overrun), unless the request was stopped. Its search ends at the plan's limit
  // less this step's reserve, which a loaded machine can spend before the polisher starts;
  // a polisher left a millisecond makes nothing exact, and the re-plan within the chords'
  // error then has no time either.
  PolishOptions polish = context.options.polish;
  const double least_s = first_plan && !context.request.deadline.Stopped()
                             ? context.TimeLeftSeconds() + polish.completion_overrun_s
                             : 1e-3;
  polish.time_limit_s = std::min(polish.time_limit_s, std::max({1e-3, least_s, context.TimeLeftSeconds()}));
  // Under guidance no more than the window's own share (at least 50 ms): the polisher
  // took 0.2-0.4 s of 0.3 s shares on octopod stones; a window it cannot polish in
  // time is planned again within the chords' error (below).
  if (context.guided && context.options.window_time_slack > 0.0) {
    polish.time_limit_s = std::min(polish.time_limit_s, std::max(0.05, search.bnb.time_limit_s));
  }
  ExactWindow out;
  const PlanClock::time_point polish_start = PlanClock::now();
  out.polished = PolishWindow(formulation, search.result.x, polish);
  out.polish_s = SecondsSince(polish_start);
  out.result = std::move(search.result);
  if (!out.polished.report.message.empty() && !polish.replan_when_inexact) out.note = out.polished.report.message;
  if (!(polish.enabled && polish.replan_when_inexact && !out.polished.report.exact)) return out;
  // A window the polisher cannot make exact is planned again within the chords' error
  // (exact_window.h).
  BranchAndBoundOptions bnb = std::move(search.bnb);
  bnb.deadline = context.request.deadline.Within(context.TimeLeftSeconds());
  // The re-plan's own polisher gets only what is left of the plan's time: its plan is
  // exact without it (exact_window.h), so it never extends the overrun above.
  polish.time_limit_s = std::min(polish.time_limit_s, std::max(1e-3, context.TimeLeftSeconds()));
  out.replan_tried = true;
  out.replan = ReplanWithinChordError(formulation, context.solvers, bnb, polish, &out.result.x, &context.goal);
  out.note = out.replan.note;
  if (!out.replan.planned) return out;
  const double polish_s = out.polished.report.time_s;
  out.result = out.replan.result;
  out.polished = std::move(out.replan.polished);
  out.polished.report.time_s += polish_s;  // both polishes
  return out;
}

void RecordExactness(const ExactWindow& exact, Plan* plan) {
  if (exact.replan.planned) {
    plan->nodes += exact.replan.result.nodes;
    plan->relaxations += exact.replan.result.relaxations;
    plan->relaxation_fallbacks += exact.replan.result.fallbacks;
  }
  plan->window_records.back().polished = exact.polished.report.accepted;
  plan->window_records.back().replanned = exact.replan.planned;
}

}  // namespace mfp
