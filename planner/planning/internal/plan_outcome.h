#pragma once
// The plan's outcome: its status and message where the windows end (a rejected request,
// the time limit, a window with no plan, a stuck horizon) and once they have ended, and
// what the caller hears after each accepted window. Private to planner/planning.
#include <functional>
#include <string>

#include "planner/formulation/plan.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/planning/internal/window_exactness.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

// A plan with no steps that answers a bad request.
Plan Rejected(SolveStatus status, const std::string& message);

// The plan's time (or the caller's deadline) ran out before the next window.
void EndOnTimeLimit(const PlanContext& context, HorizonState* state);
// The window's MIQP is infeasible as built (MiqpFormulation::infeasible_reason).
void EndOnInfeasibleWindow(const std::string& reason, HorizonState* state);
// The window's search found no plan (and no retry is left): the first window's status is
// the plan's; a later one leaves the plan so far standing (unguided, a search that found
// nothing in its time share ends the plan with status time_limit; one that ends with an
// error status passes it on). A search without a plan says in the message whether its
// root relaxation was solved.
void EndOnFailedSearch(const PlanContext& context, const BranchAndBoundResult& result, HorizonState* state);
// Neither the polisher nor the re-plan within the chords' error made the window exact.
// That proves nothing about the true boxes: no exact plan found, never infeasible.
void EndOnInexactWindow(const ExactWindow& exact, HorizonState* state);
// The horizon is stuck short of the goal (HorizonPolicy::Stuck) and no retry is left.
void EndStuck(const std::string& why, HorizonState* state);

// The plan has stopped making progress (HorizonPolicy::Stalled).
void EndStalled(const std::string& why, HorizonState* state);

// After an accepted window: the plan so far to request.on_plan_so_far (when it kept
// steps) and the window's progress to on_progress.
void ReportWindow(const PlanContext& context, const HorizonState& state, int kept, const ExactWindow& exact,
                  const std::function<void(const PlanProgress&)>& on_progress);

// The plan once the windows have ended: why it stops short of the goal, the polisher's
// note, status partial for a whole plan short of the goal (its steps up to its best
// point: HorizonState::ReturnToBest), its gap and solve time.
Plan FinishPlan(const PlanContext& context, HorizonState* state);

}  // namespace mfp
