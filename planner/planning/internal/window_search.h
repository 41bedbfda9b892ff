#pragma once
// One window's search: its share of the plan's time, the plans it starts from (the
// client's previous plan, plans along the route, one relax-and-fix plan at the root) and
// the branch-and-bound itself, with a replanning robot's bounded first search. Private
// to planner/planning.
#include <Eigen/Core>

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"
#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

// The time kept from a window search's deadline for its exactness step [s]
// (PolishOptions::reserve_fraction): the polisher and, when it fails, the re-plan.
double ExactnessReserve(const PlanContext& context);

// The search options of the next window: options.branch_and_bound with the window's time
// share of remaining_s (an even split over the windows the step budget leaves, at least
// half the time; under guidance WindowTimeShare over the windows the route still needs),
// anytime searches under guidance, and a deadline within the plan's time limit (and
// anytime_window_cap shares for an anytime search).
BranchAndBoundOptions WindowSearchOptions(const PlanContext& context, const HorizonState& state,
                                          double remaining_s, const MiqpFormulation& formulation);

struct WindowSearch {
  BranchAndBoundResult result;
  BranchAndBoundOptions bnb;  // the options the search ended with (a bounded replan's time limit)
};

// Searches the window's MIQP from bnb (WindowSearchOptions). first_window: the client's
// previous plans (PlanRequest::warm_start) seed it, and a robot standing on one gets a
// search bounded by replan_time_s that answers the best of its own plan, the previous
// plan's assignment and the route's plans, each solved as a QP (status feasible), or,
// when none of them is a plan, goes on as the full search.
// Fills the record's search fields (time limit, status, nodes, relaxations, times).
WindowSearch SearchWindow(const PlanContext& context, const MiqpFormulation& formulation, BranchAndBoundOptions bnb,
                          bool first_window, const Eigen::Vector2d& stance_centre, WindowRecord* record);

}  // namespace mfp
