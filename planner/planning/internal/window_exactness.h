#pragma once
// A searched window made exact: its plan polished with exact sin/cos (window_polisher.h)
// and, when the polisher cannot make it exact, planned again within the chords' error
// (exact_window.h). Private to planner/planning.
#include <string>

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"
#include "planner/planning/internal/exact_window.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/planning/internal/window_polisher.h"
#include "planner/planning/internal/window_search.h"

namespace mfp {

struct ExactWindow {
  BranchAndBoundResult result;  // the plan to keep: the search's, or the re-plan's
  PolishedWindow polished;      // its footsteps and the polisher's account (both polishes' time)
  ExactReplan replan;           // the re-plan within the chords' error, when it was tried
  bool replan_tried = false;
  double polish_s = 0.0;        // wall time of the first polish
  std::string note;             // for the plan's message: why the polished plan was not used, or the re-plan's account

  // The re-plan was tried and found no plan: the window has no exact plan.
  bool NoExactPlan() const { return replan_tried && !replan.planned; }
  // The MIQP that result.x solves.
  const MiqpFormulation& Used(const MiqpFormulation& window) const {
    return replan.planned ? *replan.formulation : window;
  }
};

// Polishes the search's plan within the polisher's time (at most the plan's time left
// and, under guidance, the window's share; for the plan's first plan, first_plan, at
// least polish.completion_overrun_s) and re-plans when it stays inexact
// (PolishOptions::replan_when_inexact).
ExactWindow MakeWindowExact(const PlanContext& context, const MiqpFormulation& formulation, WindowSearch search,
                            bool first_plan);

// Counts a successful re-plan's work in the plan and marks the window's record (the last).
void RecordExactness(const ExactWindow& exact, Plan* plan);

}  // namespace mfp
