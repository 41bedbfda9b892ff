#include "planner/planning/internal/window_search.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "planner/planning/internal/goal_keeping.h"
#include "planner/planning/internal/relax_and_fix.h"
#include "planner/planning/internal/route_proposals.h"
#include "planner/planning/internal/warm_start.h"
#include "planner/planning/internal/window_budget.h"

namespace mfp {
namespace {

// The plans a window's search starts from.
struct WindowSeeds {
  std::vector<Eigen::VectorXd> proposals;   // offered once at the root
  bool stance_matched = false;              // the start stance stands on a previous plan
  bool bounded_replan = false;              // a robot on its previous plan, replan_time_s > 0
  std::optional<Eigen::VectorXd> warm_plan; // bounded replan: the best of the previous plan's and the route's plans
};

WindowSeeds SeedWindow(const PlanContext& context, const MiqpFormulation& formulation, const BranchAndBoundOptions& bnb,
                       bool first_window, const Eigen::Vector2d& stance_centre) {
  const PlannerOptions& options = context.options;
  // The first window of a replanning request starts from the client's previous plan.
  WarmStart warm_start;
  for (const std::vector<Footstep>& previous : first_window ? context.request.warm_start
                                                            : std::vector<std::vector<Footstep>>{}) {
    WarmStart w = WarmStartFrom(formulation, previous, options.warm_start_match_m);
    warm_start.stance_matched = warm_start.stance_matched || w.stance_matched;
    for (Eigen::VectorXd& x : w.proposals) warm_start.proposals.push_back(std::move(x));
  }
  WindowSeeds seeds;
  seeds.stance_matched = warm_start.stance_matched;
  seeds.bounded_replan = warm_start.stance_matched && options.replan_time_s > 0.0;
  // Plans that follow the route (route_proposals.h): on fields of many small regions
  // the search's own first plans barely move the body.
  std::vector<Eigen::VectorXd> route_plans;
  if (context.guided && options.route_proposals) {
    route_plans = RouteProposals(formulation, context.guide, RouteProgress(context.guide, stance_centre),
                                 options.route_proposal);
  }
  if (!seeds.bounded_replan) {
    seeds.proposals = std::move(warm_start.proposals);
    for (Eigen::VectorXd& x : route_plans) seeds.proposals.push_back(std::move(x));
    return seeds;
  }
  // A bounded replan solves the previous plan's assignment and the route's plans first
  // (each a QP of a few milliseconds, not cut by the budget): the best of them is the
  // answer when the bounded search finds nothing better by replan_time_s. The route's
  // plans walk on where the previous plan only marks time at its end (with the previous
  // plan alone a robot on the stepping stones walked in place at the start pad's edge).
  // The search does not start from them: with an incumbent from its root the search goes
  // best-bound at once and, cut short, never dives to a better plan (the robot kept the
  // first plan it got), so it dives for its own.
  if (!warm_start.proposals.empty() || !route_plans.empty()) {
    for (Eigen::VectorXd& x : route_plans) warm_start.proposals.push_back(std::move(x));
    seeds.warm_plan = SolveWarmStart(formulation, warm_start.proposals, *context.solvers.front(), bnb.deadline,
                                     bnb.feasibility_tolerance);
  }
  return seeds;
}

// One relax-and-fix plan for the search's root, its stages searched with the window's
// options (bnb) for rf.time_share of its time, at most search_left_s (a seed deferred
// until the search's first nodes must not outlast the search's own time limit). Without a first plan (the root's roundings
// and the quick dive found none) its completion may overrun the window's deadline as the
// first plan's work does (BranchAndBoundOptions::first_plan_overrun_s): the stages end on
// that deadline when the dive took the time, and the completion's rounding is then the
// window's only plan.
RelaxAndFixResult RelaxAndFixSeed(const PlanContext& context, const MiqpFormulation& formulation,
                                  const BranchAndBoundOptions& bnb, bool without_first_plan, double search_left_s) {
  RelaxAndFixOptions rf = context.options.relax_and_fix;
  rf.stage = bnb;
  rf.completion_overrun_s = without_first_plan ? bnb.first_plan_overrun_s : 0.0;
  rf.stage.time_limit_needs_incumbent = false;  // a stage out of time is completed by rounding
  // Stage searches are small (nodes_per_stage): strong branching would cost them more
  // than it saves, and their plans came out worse (docs/measurements.md).
  if (rf.stage.branching == BranchingRule::kReliability) rf.stage.branching = BranchingRule::kGroupOrder;
  rf.time_limit_s = std::min(rf.time_share * bnb.time_limit_s, search_left_s);
  return rf.two_paths ? RelaxAndFixTwoPaths(formulation, context.solvers, rf) : RelaxAndFix(formulation, context.solvers, rf);
}

// The quick first plan of a seeded window whose root roundings found none
// (RelaxAndFixOptions::first_plan_dive): one node per stage, the stage roundings on, one
// path (each stage's QPs take milliseconds). The rounding dive first (rf.rounding_dive),
// then, when it finds no plan, the stage-search dive with a share of its own: cut short,
// it still ends with its rounding's complete plan (RelaxAndFix), where one given what the
// rounding dive left could end with none. The relaxations of both are counted. Both are
// the window's first plan's work: they run under its deadline extended by
// bnb.first_plan_overrun_s, so a root relaxation solved in time is carried through to a
// plan, and each one's share (time_share of the window's time, counted from its own
// start) reaches at least that deadline: a share ending sooner cut a dive that began early
// while it still had time, and a dive's early stage points do not round to a plan.
RelaxAndFixResult RelaxAndFixDive(const PlanContext& context, const MiqpFormulation& formulation,
                                  const BranchAndBoundOptions& bnb, const Eigen::VectorXd& root_x) {
  RelaxAndFixOptions rf = context.options.relax_and_fix;
  rf.stage = bnb;
  rf.stage.deadline = bnb.deadline.ExtendedBy(bnb.first_plan_overrun_s);
  rf.stage.time_limit_needs_incumbent = false;
  rf.time_limit_s = rf.time_share * bnb.time_limit_s;
  // At least to the first plan's deadline, but no longer than the window's own time and
  // the overrun, counted from the dive's start: in a plan of several windows whose
  // deadline is the plan's, one window's dive does not take the later windows' time.
  if (rf.stage.deadline.finite()) {
    rf.time_limit_s = std::max(rf.time_limit_s, std::min(rf.stage.deadline.RemainingSeconds(),
                                                         bnb.time_limit_s + bnb.first_plan_overrun_s));
  }
  RelaxAndFixResult rounding;
  if (rf.rounding_dive) {
    rounding = RoundingDive(formulation, *context.solvers.front(), root_x, rf);
    if (rounding.x) return rounding;
  }
  RelaxAndFixResult r = RelaxAndFix(formulation, context.solvers, DiveOptions(rf));
  r.stages += rounding.stages;
  r.relaxations += rounding.relaxations;
  r.fallbacks += rounding.fallbacks;
  return r;
}

}  // namespace

double ExactnessReserve(const PlanContext& context) {
  const PolishOptions& polish = context.options.polish;
  if (!polish.enabled) return 0.0;
  return std::min({polish.time_limit_s, polish.reserve_fraction * context.time_limit_s,
                   0.5 * std::max(0.0, context.TimeLeftSeconds())});
}

BranchAndBoundOptions WindowSearchOptions(const PlanContext& context, const HorizonState& state, double remaining_s,
                                          const MiqpFormulation& formulation) {
  const PlannerOptions& options = context.options;
  const int window = context.window_steps;
  BranchAndBoundOptions bnb = options.branch_and_bound;
  // Each window gets its share of the remaining time, and at least half of it when
  // few windows are left (later windows are usually shorter, near the goal).
  const int windows_left = (context.max_steps - state.planned + window - 1) / window;
  bnb.time_limit_s = std::max(remaining_s / windows_left, 0.5 * remaining_s);
  if (context.guided && options.window_time_slack > 0.0) {
    // Under guidance: a share from the windows the route still needs.
    WindowBudgetInput budget;
    budget.remaining_s = remaining_s;
    const double progress = RouteProgress(context.guide, StanceCentreXY(state.stance));
    budget.route_left_m = context.guide.length_m - progress;
    budget.route_covered_m = progress - state.start_progress_m;
    budget.accepted_windows = state.accepted_windows;
    budget.prior_advance_m = context.robot.d_lim_m * std::max(1, window / context.robot.num_legs());
    budget.slack = options.window_time_slack;
    bnb.time_limit_s = WindowTimeShare(budget);
  }
  bnb.time_limit_needs_incumbent = context.guided && options.anytime_windows;
  // A first plan's roundings may finish past the deadline by the overrun the exactness
  // step's completion has: a window whose root was solved in time ends with a plan.
  bnb.first_plan_overrun_s = options.polish.completion_overrun_s;
  // No window runs past the whole plan's limit less the exactness step's reserve
  // (PolishOptions::reserve_fraction), whatever it is given, nor, running on to its first
  // plan, past anytime_window_cap shares.
  const double time_left_s = context.TimeLeftSeconds() - ExactnessReserve(context);
  bnb.deadline = context.request.deadline.Within(
      bnb.time_limit_needs_incumbent ? std::min(time_left_s, options.anytime_window_cap * bnb.time_limit_s)
                                     : time_left_s);
  // A window aiming at the goal whose plan reaches it keeps it through re-certification.
  bnb.recertify_within = GoalKeeping(formulation, context.goal);
  if (options.snap_yaw_segments) {
    bnb.equivalent_point = [&formulation](const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                          Eigen::VectorXd* x) {
      return formulation.SnapYawToOneSegment(lower, upper, x);
    };
  }
  return bnb;
}

WindowSearch SearchWindow(const PlanContext& context, const MiqpFormulation& formulation, BranchAndBoundOptions bnb,
                          bool first_window, const Eigen::Vector2d& stance_centre, WindowRecord* record) {
  const PlannerOptions& options = context.options;
  bool seeded = !options.relax_and_fix.enabled ||
                formulation.num_configurations() - 1 < options.relax_and_fix.min_configurations;
  WindowSeeds seeds = SeedWindow(context, formulation, bnb, first_window, stance_centre);
  bool bounded_replan = seeds.bounded_replan;
  record->warm_matched = seeds.stance_matched;
  record->bounded_replan = seeds.bounded_replan;
  // A search that stalls ends (BranchAndBoundOptions::stall_time_fraction), except a
  // bounded replan's, which must dive for a plan of its own.
  if (context.guided && !bounded_replan) bnb.stall_time_fraction = options.window_stall_fraction;
  const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) {
    std::vector<Eigen::VectorXd> proposals = formulation.RoundAlongPlan(relaxed);
    proposals.insert(proposals.end(), seeds.proposals.begin(), seeds.proposals.end());
    seeds.proposals.clear();  // offered once, at the root
    return proposals;
  };
  bool without_first_plan = false;  // the roundings found no plan, nor did the quick dive
  PlanClock::time_point search_start{};  // set as the search starts, before any heuristic runs
  int heuristic_fallbacks = 0;
  // The root, once its roundings are completed: one relax-and-fix plan (the workers are
  // idle meanwhile).
  bnb.root_heuristic = [&](const Eigen::VectorXd&) {
    std::vector<Eigen::VectorXd> plans;
    if (seeded) return plans;
    seeded = true;
    const PlanClock::time_point rf_start = PlanClock::now();
    // A seed that may have waited for the search's first nodes (the search holds a plan)
    // gets no more than the search has left; one that must give the first plan keeps its
    // whole share.
    const double search_left_s = without_first_plan ? bnb.time_limit_s
                                                    : std::max(0.0, bnb.time_limit_s - SecondsSince(search_start));
    RelaxAndFixResult r = RelaxAndFixSeed(context, formulation, bnb, without_first_plan, search_left_s);
    if (r.x) plans.push_back(std::move(*r.x));
    record->heuristic_s += SecondsSince(rf_start);
    record->heuristic_relaxations += r.relaxations;
    heuristic_fallbacks += r.fallbacks;
    return plans;
  };
  bnb.root_heuristic_after_nodes = options.relax_and_fix.after_nodes;
  bnb.root_heuristic_wait_gap = options.relax_and_fix.wait_gap;
  // Before it, when the roundings found no plan: the quick dive (the search calls this
  // only then, which is also how the seed learns that it is without a first plan).
  if (!seeded) {
    bnb.first_plan_heuristic = [&](const Eigen::VectorXd& root_x) {
      std::vector<Eigen::VectorXd> plans;
      if (seeded) return plans;  // a bounded replan's second search: its first had the root
      without_first_plan = true;
      if (!options.relax_and_fix.first_plan_dive) return plans;
      const PlanClock::time_point dive_start = PlanClock::now();
      RelaxAndFixResult r = RelaxAndFixDive(context, formulation, bnb, root_x);
      without_first_plan = !r.x;
      if (r.x) plans.push_back(std::move(*r.x));
      record->heuristic_s += SecondsSince(dive_start);
      record->heuristic_relaxations += r.relaxations;
      heuristic_fallbacks += r.fallbacks;
      return plans;
    };
  }
  const double window_time_limit_s = bnb.time_limit_s;
  const bool window_needs_incumbent = bnb.time_limit_needs_incumbent;
  if (bounded_replan) bnb.time_limit_s = std::min(bnb.time_limit_s, options.replan_time_s);
  // With a plan from the previous plan's or the route's assignments solved, the bounded
  // search ends at replan_time_s with or without a plan of its own: that plan is its answer. An anytime search would
  // run on to its first plan, up to anytime_window_cap whole shares (in the stones soak
  // the slowest replies were such searches, 0.3-0.4 s against a 0.03 s budget).
  if (bounded_replan && seeds.warm_plan) bnb.time_limit_needs_incumbent = false;
  search_start = PlanClock::now();
  BranchAndBoundResult result = SolveBranchAndBound(formulation.miqp(), context.solvers, bnb, rounding);
  bnb.time_limit_needs_incumbent = window_needs_incumbent;
  const std::optional<Eigen::VectorXd>& warm_plan = seeds.warm_plan;
  if (bounded_replan && warm_plan &&
      (!HasPlan(result.status) || formulation.miqp().Objective(*warm_plan) < result.objective)) {
    result.status = SolveStatus::kFeasible;
    result.x = *warm_plan;
    result.objective = formulation.miqp().Objective(*warm_plan);
    result.bound = std::min(result.bound, result.objective);
  }
  if (bounded_replan && !HasPlan(result.status) && result.status != SolveStatus::kInfeasible) {
    // No plan in the budget (and none proven impossible): the full search.
    bnb.time_limit_s = std::max(0.0, window_time_limit_s - result.solve_time_s);
    const BranchAndBoundResult first = result;
    result = SolveBranchAndBound(formulation.miqp(), context.solvers, bnb, rounding);
    result.nodes += first.nodes;
    result.relaxations += first.relaxations;
    result.node_solve_iterations += first.node_solve_iterations;
    result.node_solve_time_s += first.node_solve_time_s;
    result.node_fallbacks += first.node_fallbacks;
    result.fallbacks += first.fallbacks;
    result.fallback_time_s += first.fallback_time_s;
    bounded_replan = false;
    record->replan_fell_back = true;
  }
  // Cut short by the replanning budget, not by the request's time: a plan, unproven.
  if (bounded_replan && result.status == SolveStatus::kTimeLimit &&
      context.request.deadline.RemainingSeconds() > 0.0 && context.TimeLeftSeconds() > 0.0) {
    result.status = SolveStatus::kFeasible;
  }
  record->search_s = SecondsSince(search_start);
  record->time_limit_s = bnb.time_limit_s;
  record->status = result.status;
  record->nodes = result.nodes;
  record->relaxations = result.relaxations + record->heuristic_relaxations;
  record->fallbacks = result.fallbacks + heuristic_fallbacks;
  bnb.root_heuristic = nullptr;  // they refer to this call's locals
  bnb.first_plan_heuristic = nullptr;
  return WindowSearch{std::move(result), std::move(bnb)};
}

}  // namespace mfp
