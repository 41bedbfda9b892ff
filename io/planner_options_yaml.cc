#include "io/planner_options_yaml.h"

#include <cmath>
#include <utility>

#include "base/check.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {
namespace {

using P = PlannerOptions;
using S = StanceRouteOptions;
using Table = OptionTable<P>;

// The top of the block: the plan's size, time and tolerances.
void AddPlanKeys(Table* t) {
  t->push_back(Opt("max_steps", At(&P::default_max_steps), 0, 100000,
                   "new footsteps in a whole plan when the request gives none (0: route.step_budget times the "
                   "route at d_lim per configuration, at least 12 x legs)"));
  t->push_back(Opt("window", At(&P::default_window_steps), 0, 1000,
                   "new footsteps per MIQP window when the request gives none (0: 2 x legs)"));
  t->push_back(Opt("time_limit", At(&P::default_time_limit_s), 1e-3, 3600,
                   "time for a whole plan when the request gives none").Unit("s"));
  t->push_back(Opt("goal_tolerance", At(&P::goal_tolerance_m), 1e-4, 10,
                   "every final foot within this of its goal spot").Unit("m"));
  t->push_back(Opt("goal_yaw_tolerance", At(&P::goal_yaw_tolerance_rad), 1e-4, M_PI,
                   "final body yaw within this of the goal yaw").Unit("rad"));
  t->push_back(Opt("goal_position_tolerance", At(&P::goal_position_tolerance_m), 0, 10,
                   "a goal stance with a foot spot on no region is moved to the nearest stance on regions at most "
                   "this far (route guidance; beyond it: invalid_goal)").Unit("m"));
  t->push_back(Opt("goal_heading_tolerance", At(&P::goal_heading_tolerance_rad), 0, M_PI,
                   "... and turned at most this much").Unit("rad"));
  t->push_back(Opt("goal_search.step", At(&P::goal_search_step_m), 1e-3, 1,
                   "grid step of the search for that stance").Unit("m").Advanced());
  t->push_back(Opt("goal_search.yaw_step", At(&P::goal_search_yaw_step_rad), 1e-3, M_PI,
                   "turn step of the search for that stance").Unit("rad").Advanced());
  t->push_back(Opt("goal_search.report_step", At(&P::goal_report_step_m), 1e-3, 1,
                   "grid step of the search, beyond the tolerances, for the nearest stance on regions that "
                   "invalid_goal names").Unit("m").Advanced());
  t->push_back(Opt("goal_search.report_radius", At(&P::goal_report_radius_m), 0, 10,
                   "... out to this distance (0: name none)").Unit("m").Advanced());
  t->push_back(Opt("stop_report.step", At(&P::stop_report_step_l_bnd), 0.01, 4,
                   "a plan stopped short of the goal names the first gap on the way ahead, sampled this many l_bnd "
                   "apart (at least 1 mm)").Advanced());
  t->push_back(Opt("stop_report.max_samples", At(&P::stop_report_max_samples), 2, 1000000,
                   "... at most this many samples (a longer way is sampled more sparsely)").Advanced());
  t->push_back(Opt("goal_search.seen_footholds", At(&P::goal_seen_footholds),
                   "with no stance on regions within the goal tolerances, plan to the nearest stance whose spots off "
                   "the regions stand on flat seen floor (a foothold region each)").Advanced());
  t->push_back(Opt("goal_search.foothold_margin", At(&P::goal_foothold_margin_m), 0, 1,
                   "such a foothold has seen floor flat within a cell for the foot radius, this margin, one map "
                   "cell and the foothold square's half diagonal around its spot").Unit("m").Advanced());
  t->push_back(Opt("goal_search.foothold_half_side", At(&P::goal_foothold_half_side_m), 0, 10,
                   "a foothold is a square about its spot of this half side at first (0: half goal_tolerance)")
                   .Unit("m").Advanced());
  t->push_back(Opt("goal_search.foothold_max_half_side", At(&P::goal_foothold_max_half_side_m), 0, 10,
                   "... doubled while its disk stays flat, up to this half side (0: the robot's d_lim)")
                   .Unit("m").Advanced());
  t->push_back(Opt("start_tolerance", At(&P::start_tolerance_m), 0, 1,
                   "a start foot may lie this far off its region").Unit("m"));
  t->push_back(Opt("start_seen_footholds", At(&P::start_seen_footholds),
                   "a start foot on no region but on flat seen floor gets a foothold region (as a goal spot's, "
                   "goal_search.foothold_margin) that the first steps may use").Advanced());
  t->push_back(Opt("warm_start_match", At(&P::warm_start_match_m), 0, 1,
                   "a previous plan seeds the search when every start foot lies this close to one of its steps")
                   .Unit("m"));
  t->push_back(Opt("replan_time", At(&P::replan_time_s), 0, 3600,
                   "search time of the first window of a robot standing on its previous plan (0: its share)")
                   .Unit("s"));
  t->push_back(Opt("snap_yaw_segments", At(&P::snap_yaw_segments),
                   "a relaxed yaw on a segment breakpoint is set to that segment before branching")
                   .Advanced());
}

// windows: how the receding windows share time, retry and stop.
void AddWindowKeys(Table* t) {
  t->push_back(Opt("windows.max_horizon", At(&P::max_horizon_windows), 1, 100,
                   "a failed window is planned again with up to this many times the window's steps (1: no retries)")
                   .Alias("max_horizon_windows").Advanced());
  t->push_back(Opt("windows.max_without_progress", At(&P::max_windows_without_progress), 0, 1000,
                   "a plan whose way left has not shrunk over this many windows ends partial at its best point (0: off)"));
  t->push_back(Opt("windows.time_slack", At(&P::window_time_slack), 0.0, 1000.0,
                   "a guided window's time: this many fair shares of the time left (0: the even split)")
                   .Alias("window_time_slack").Advanced());
  t->push_back(Opt("windows.stall_fraction", At(&P::window_stall_fraction), 0.0, 1.0,
                   "a guided window's search ends once its plan has not improved for this fraction of its share (0: off)")
                   .Alias("window_stall_fraction").Advanced());
  t->push_back(Opt("windows.anytime", At(&P::anytime_windows),
                   "a guided window's time share ends its search only once it has a plan")
                   .Alias("anytime_windows").Advanced());
  t->push_back(Opt("windows.anytime_cap", At(&P::anytime_window_cap), 1.0, 1000.0,
                   "... for at most this many times its share")
                   .Alias("anytime_window_cap").Advanced());
}

// route: the region graph's route, local goals and route proposals.
void AddRouteKeys(Table* t) {
  t->push_back(Opt("route.guidance", At(&P::route_guidance),
                   "a route over the regions answers no_route early, sets the step budget and guides the windows")
                   .Alias("route_guidance"));
  t->push_back(Opt("route.local_goal_lookahead", At(&P::local_goal_lookahead_m), -1.0, 1000.0,
                   "each window aims this far along the route (0: the goal itself; negative: about one window's walk)")
                   .Alias("local_goal_lookahead").Unit("m").Advanced());
  t->push_back(Opt("route.local_goal_detour_ratio", At(&P::local_goal_detour_ratio), 1.0, 100.0,
                   "local goals while the route left is longer than this times the straight line to the goal")
                   .Alias("local_goal_detour_ratio").Advanced());
  t->push_back(Opt("route.stance_route", At(&P::stance_route),
                   "local goals follow a search over whole-body stances, not the region graph's centres")
                   .Alias("stance_route").Advanced());
  t->push_back(Opt("stance_search.cell", In(&P::stance_search, &S::cell_m), 0.005, 1.0,
                   "grid step of that search's body positions (grown on large maps to stay within max_cells)")
                   .Unit("m").Advanced());
  t->push_back(Opt("stance_search.max_cells", In(&P::stance_search, &S::max_cells), 1000, 10000000,
                   "body positions of that grid at most").Advanced());
  t->push_back(Opt("stance_search.body_blocked_cell", In(&P::stance_search, &S::body_blocked_cell_m), 0.005, 1.0,
                   "before a route is refused for the body, the search runs again on this finer grid")
                   .Unit("m").Advanced());
  t->push_back(Opt("stance_search.headings", In(&P::stance_search, &S::headings), 1, 360,
                   "body yaws that search tries, evenly spaced over a full turn").Advanced());
  t->push_back(Opt("stance_search.fine_headings", In(&P::stance_search, &S::fine_headings), 1, 360,
                   "... and where the body check refused poses, again with this many (when more)").Advanced());
  t->push_back(Opt("stance_search.route_yaw_unusable_share",
                   In(&P::stance_search, &S::route_yaw_unusable_share), 0.0, 1.0,
                   "windows hold the route's yaws when this share of its poses cannot stand at the goal's "
                   "heading (else they aim at the goal's heading)")
                   .Advanced());
  t->push_back(Opt("stance_search.turn_cost", In(&P::stance_search, &S::turn_cost_m), 0.0, 100.0,
                   "cost of turning by one heading, as a distance walked").Unit("m").Advanced());
  t->push_back(Opt("stance_search.tight_cost_factor", In(&P::stance_search, &S::tight_cost_factor), 1.0, 1000.0,
                   "cost factor of a pose with a nominal foot off every region, or a body within body_margin of "
                   "an obstacle").Advanced());
  t->push_back(Opt("stance_search.support_radius", In(&P::stance_search, &S::support_radius_l_bnd), 0.1, 10.0,
                   "a pose is usable when each nominal foot has a region within this many l_bnd").Advanced());
  t->push_back(Opt("stance_search.body_overlap_share", In(&P::stance_search, &S::body_overlap_share), 0.0, 1.0,
                   "share of the body's plan box an obstacle may cover before a pose is unusable").Advanced());
  t->push_back(Opt("stance_search.body_margin", In(&P::stance_search, &S::body_margin_m), 0.0, 1.0,
                   "room the route keeps between the body's plan box and obstacles where it can").Unit("m").Advanced());
  t->push_back(Opt("map_body_obstacles", At(&P::map_body_obstacles),
                   "on an occupancy map, the body keeps clear of the map's occupied voxels above the floor "
                   "(when the robot's body is known)"));
  t->push_back(Opt("route.step_budget", At(&P::route_step_budget), 1.0, 1000.0,
                   "default step budget: configurations for this many times the route's length at d_lim each")
                   .Alias("route_step_budget").Advanced());
  t->push_back(Opt("route.proposals", At(&P::route_proposals),
                   "each guided window's search starts from plans that walk the route at a few speeds")
                   .Alias("route_proposals").Advanced());
  t->push_back(ListOpt("route.proposal_speeds", In(&P::route_proposal, &RouteProposalOptions::advance_fractions),
                       0.0, true, 2.0, "body advance per configuration of the route proposals, fractions of d_lim")
                   .Alias("route_proposal_speeds").Advanced());
  t->push_back(Opt("route.proposal_yaw_rate", In(&P::route_proposal, &RouteProposalOptions::yaw_rate_fraction),
                   0.0, 1.0, "route proposals turn by at most this fraction of max_yaw_change per configuration")
                   .Alias("route_proposal_yaw_rate").Advanced());
}

void AddSolverKeys(Table* t) {
  t->push_back(EnumOpt("solvers.relaxation_solver", In(&P::solvers, &RelaxationSolverOptions::backend),
                       std::vector<std::pair<std::string, RelaxationBackend>>{
                           {"ipm", RelaxationBackend::kInteriorPointWithIpoptFallback},
                           {"ipopt", RelaxationBackend::kIpopt},
                           {"dualqp", RelaxationBackend::kDualActiveSetWithFallbacks}},
                       "QP solver of the relaxations: mfp's interior point (Ipopt as fallback), Ipopt alone, or "
                       "mfp's dual active set started from the parent node's active set (interior point for roots, large QPs "
                       "and as fallback)")
                   .Alias("relaxation_solver"));
  t->push_back(Opt("solvers.threads", In(&P::solvers, &RelaxationSolverOptions::threads), 1, 64,
                   "branch-and-bound workers solving node relaxations at once")
                   .Alias("threads"));
}

void AddFormulationKeys(Table* t) {
  using F = FormulationOptions;
  t->push_back(Opt("formulation.yaw_segment", In(&P::formulation, &F::yaw_segment_rad), 0.02, M_PI,
                   "width of one sin/cos chord segment").Alias("yaw_segment").Unit("rad").Advanced());
  t->push_back(Opt("formulation.yaw_margin", In(&P::formulation, &F::yaw_margin_rad), 0, M_PI,
                   "yaw range: [min(start, goal) - margin, max(start, goal) + margin]")
                   .Alias("yaw_margin").Unit("rad").Advanced());
  t->push_back(EnumOpt("formulation.region_encoding", In(&P::formulation, &F::region_encoding),
                       std::vector<std::pair<std::string, RegionEncoding>>{
                           {"big_m", RegionEncoding::kBigM}, {"convex_hull", RegionEncoding::kConvexHull}},
                       "how a step's choice of region is written").Alias("region_encoding").Advanced());
  t->push_back(EnumOpt("formulation.yaw_encoding", In(&P::formulation, &F::yaw_encoding),
                       std::vector<std::pair<std::string, YawEncoding>>{
                           {"big_m", YawEncoding::kBigM}, {"convex_hull", YawEncoding::kConvexHull}},
                       "how a configuration's sin/cos segment is written").Alias("yaw_encoding").Advanced());
  t->push_back(EnumOpt("formulation.group_order", In(&P::formulation, &F::group_order),
                       std::vector<std::pair<std::string, GroupOrder>>{
                           {"plan", GroupOrder::kPlan}, {"segments_first", GroupOrder::kSegmentsFirst}},
                       "order of the one-of groups that search.branching group_order follows")
                   .Advanced());
  t->push_back(Opt("formulation.prune_unreachable_regions", In(&P::formulation, &F::prune_unreachable_regions),
                   "drop region binaries a step cannot reach from the start stance")
                   .Alias("prune_unreachable_regions").Advanced());
  t->push_back(Opt("formulation.monotone_trimming", In(&P::formulation, &F::monotone_trimming),
                   "trimmed steps form a suffix (removes symmetric solutions)").Alias("monotone_trimming").Advanced());
  t->push_back(Opt("formulation.clip_yaw_to_reach", In(&P::formulation, &F::clip_yaw_to_reach),
                   "bound each configuration's yaw by what it can reach from the start")
                   .Alias("clip_yaw_to_reach").Advanced());
  t->push_back(Opt("formulation.trimmed_configurations_hold_yaw",
                   In(&P::formulation, &F::trimmed_configurations_hold_yaw),
                   "a configuration whose first step is trimmed keeps the yaw of the one before")
                   .Alias("trimmed_configurations_hold_yaw").Advanced());
  t->push_back(Opt("formulation.body_regions", In(&P::formulation, &F::body_regions),
                   "keep the body's plan box in obstacle-free body regions in the windows (with body obstacles)"));
  t->push_back(Opt("formulation.body_margin", In(&P::formulation, &F::body_margin_m), 0, 0.5,
                   "the body box is kept this far inside its body region").Unit("m").Advanced());
  t->push_back(Opt("formulation.max_body_regions", In(&P::formulation, &F::max_body_regions), 1, 64,
                   "body regions grown per window (one binary per configuration each)").Advanced());
}

std::vector<std::pair<std::string, NodeSelection>> NodeSelectionNames() {
  return {{"best_bound", NodeSelection::kBestBound},
          {"depth_first", NodeSelection::kDepthFirst},
          {"dive_then_best_bound", NodeSelection::kDiveThenBestBound},
          {"plunging", NodeSelection::kBestBoundWithPlunging}};
}

void AddSearchKeys(Table* t) {
  using B = BranchAndBoundOptions;
  auto in = [](auto B::*field) { return In(&P::branch_and_bound, field); };
  t->push_back(Opt("search.max_nodes", in(&B::max_nodes), 1, 10000000, "nodes a window's search explores at most")
                   .Alias("max_nodes"));
  t->push_back(Opt("search.relative_gap", in(&B::relative_gap), 0, 1,
                   "a window's search stops this close to its proven optimum, relative to the objective")
                   .Alias("relative_gap"));
  t->push_back(EnumOpt("search.node_selection", in(&B::node_selection), NodeSelectionNames(),
                       "which open node the search explores next").Alias("node_selection").Advanced());
  t->push_back(Opt("search.plunge_fraction", in(&B::plunge_fraction), 0, 1,
                   "plunging: go on into a child while its bound lies within this fraction of bound to incumbent")
                   .Alias("plunge_fraction").Advanced());
  t->push_back(EnumOpt("search.branching", in(&B::branching),
                       std::vector<std::pair<std::string, BranchingRule>>{
                           {"most_fractional", BranchingRule::kMostFractional},
                           {"sos1", BranchingRule::kSos1Split},
                           {"group_order", BranchingRule::kGroupOrder},
                           {"reliability", BranchingRule::kReliability}},
                       "which variable or one-of group a node branches on").Alias("branching").Advanced());
  t->push_back(Opt("search.reliability", in(&B::reliability), 0, 1000,
                   "reliability branching: observations per direction before a pseudo-cost is trusted")
                   .Alias("reliability").Advanced());
  t->push_back(Opt("search.strong_branching_candidates", in(&B::strong_branching_candidates), 0, 10000,
                   "reliability branching: most candidates strong-branched at a node")
                   .Alias("strong_branching_candidates").Advanced());
  t->push_back(Opt("search.strong_branching_lookahead", in(&B::strong_branching_lookahead), 1, 10000,
                   "reliability branching: stop after this many trials without a better score")
                   .Alias("strong_branching_lookahead").Advanced());
  t->push_back(Opt("search.rounding_heuristic", in(&B::rounding_heuristic),
                   "round relaxations and solve the fixed QP at the root and on dives")
                   .Alias("rounding_heuristic").Advanced());
  t->push_back(Opt("search.rounding_frequency", in(&B::rounding_frequency), 0, 1000000,
                   "also try rounding every this many nodes (0: the root only)")
                   .Alias("rounding_frequency").Advanced());
  t->push_back(Opt("search.bound_propagation", in(&B::bound_propagation),
                   "tighten bounds over the rows at every node first").Alias("bound_propagation").Advanced());
  t->push_back(Opt("search.group_probing", in(&B::group_probing),
                   "fix each open member of each one-of group in turn and propagate: rule out the infeasible ones, "
                   "shrink bounds to the hull of the rest (the root after its roundings, then nodes as "
                   "group_probing_interval; a node's subtree inherits its bounds)")
                   .Advanced());
  t->push_back(Opt("search.group_probing_interval", in(&B::group_probing_interval), 1, 1000,
                   "group probing: probe the nodes of depth 1, 1 + k, 1 + 2k, ... (k = this; the root after its "
                   "roundings); the others inherit the probed bounds")
                   .Advanced());
  t->push_back(Opt("search.group_probing_work", in(&B::group_probing_work), 0, 1e6,
                   "group probing: row visits a node's probing may spend, per row of the problem (0: no cap); the "
                   "branched step's groups and their neighbours first")
                   .Advanced());
  t->push_back(Opt("search.rins_frequency", in(&B::rins_frequency), 0, 1000000,
                   "once the plan has not improved for rins_after_nodes nodes, then every this many nodes (grown by "
                   "rins_backoff), while the gap is above rins_min_gap, fix the integers where the incumbent and the "
                   "node's relaxation agree and search the rest for a better plan (RINS; 0: off)")
                   .Advanced());
  t->push_back(Opt("search.rins_after_nodes", in(&B::rins_after_nodes), 0, 100000000,
                   "RINS: the first run waits until the search has processed this many nodes since its plan last "
                   "improved (0: at the root)")
                   .Advanced());
  t->push_back(Opt("search.rins_backoff", in(&B::rins_backoff), 1, 1000,
                   "RINS: a run that finds no better plan multiplies the interval to the next by this; one that does "
                   "restores rins_frequency (1: a fixed interval)")
                   .Advanced());
  t->push_back(Opt("search.rins_min_gap", in(&B::rins_min_gap), 0, 1,
                   "RINS runs only while the search's relative gap (plan to bound) is above this")
                   .Advanced());
  t->push_back(Opt("search.rins_max_nodes", in(&B::rins_max_nodes), 1, 10000000,
                   "RINS: nodes each of its sub-searches explores at most")
                   .Advanced());
  t->push_back(EnumOpt("search.rins_node_selection", in(&B::rins_node_selection), NodeSelectionNames(),
                       "RINS: which open node its sub-searches explore next (they hold the plan from their root)")
                       .Advanced());
  t->push_back(Opt("search.long_search_only", in(&B::long_search_only), 0, kAllLongSearchLevers,
                   "levers that run only while the search is long (long_search_min_nodes, long_search_nodes_left), a "
                   "sum of 1 (group probing), 2 (RINS), 4 (root cut loop: the search starts without cuts and restarts "
                   "with them once long); 0: each lever runs whenever it is on")
                   .Advanced());
  t->push_back(Opt("search.long_search_min_nodes", in(&B::long_search_min_nodes), 0, 100000000,
                   "a search is long once it has processed at least this many nodes and its time left holds "
                   "long_search_nodes_left more nodes at its mean time per node")
                   .Advanced());
  t->push_back(Opt("search.long_search_nodes_left", in(&B::long_search_nodes_left), 0, 1e9,
                   "a search is long while its time left (to its deadline and its stall limit) would hold at least "
                   "this many more nodes at its mean time per node so far (with long_search_min_nodes)")
                   .Advanced());
  t->push_back(Opt("search.reduced_cost_fixing", in(&B::reduced_cost_fixing),
                   "rule out integer values that the relaxation proves cannot beat the incumbent")
                   .Alias("reduced_cost_fixing").Advanced());
  t->push_back(Opt("search.early_cutoff", in(&B::early_cutoff),
                   "a node's relaxation stops once it cannot beat the incumbent").Alias("early_cutoff").Advanced());
  t->push_back(Opt("search.relaxation_polish", in(&B::relaxation_polish), 0.0, 1e-2,
                   "crossover: once a relaxation's interior point reaches this relative accuracy, finish from its "
                   "active set (an exact optimum, its floor equal to it) and go on only when that fails (0: off)")
                   .Advanced());
  t->push_back(Opt("search.recertify_leaves", in(&B::recertify_leaves), 0, 10000,
                   "when a window's tree is exhausted short of its gap, solve again this many of the subtrees it "
                   "settled at the lowest floors, by exact methods, to certify their floors; a window whose plan "
                   "reaches the goal keeps it, and its steps, meanwhile (0: off)")
                   .Advanced());
  t->push_back(Opt("search.root_cut_rounds", in(&B::root_cut_rounds), 0, 1000,
                   "rounds of cuts separated at the root after its first plan, before the search (0: off)")
                   .Alias("root_cut_rounds").Advanced());
  t->push_back(Opt("search.root_cut_families", in(&B::root_cut_families), 1, kAllRootCutFamilies,
                   "the root cut loop's families, a sum of 1 (c-MIR), 2 (group bounds), 4 (implied bounds), "
                   "8 (cliques)")
                   .Advanced());
  t->push_back(Opt("search.root_cut_aggregations", in(&B::root_cut_aggregations), 0, 20,
                   "rows the root cut loop's c-MIR adds to a starting row to cancel continuous variables")
                   .Advanced());
}

// relax_and_fix: the seed of each window's search. Its stage searches take the search:
// options and its time is time_share of the window's (footstep_planner.cc): there are no
// keys for them here, so none can be set and then silently replaced.
void AddRelaxAndFixKeys(Table* t) {
  using R = RelaxAndFixOptions;
  auto in = [](auto R::*field) { return In(&P::relax_and_fix, field); };
  t->push_back(Opt("relax_and_fix.enabled", in(&R::enabled), "seed each window's search with a relax-and-fix plan")
                   .Alias("relax_and_fix").Advanced());
  t->push_back(Opt("relax_and_fix.time_share", in(&R::time_share), 0.01, 1,
                   "fraction of the window's time relax-and-fix may use (its stages search with search: options)")
                   .Alias("relax_and_fix_time_share").Advanced());
  t->push_back(Opt("relax_and_fix.min_configurations", in(&R::min_configurations), 2, 100000,
                   "only windows with at least this many configurations of new steps are seeded")
                   .Alias("relax_and_fix_min_configurations").Advanced());
  t->push_back(Opt("relax_and_fix.region_hull", in(&R::hull_for_later_steps),
                   "steps after a stage's integer configurations stand in the convex hull of their regions")
                   .Alias("relax_and_fix_region_hull").Advanced());
  t->push_back(Opt("relax_and_fix.two_paths", in(&R::two_paths),
                   "with two or more workers, two single-worker runs instead of one sharing them")
                   .Alias("relax_and_fix_two_paths").Advanced());
  t->push_back(Opt("relax_and_fix.stage_tolerance", in(&R::stage_relaxation_tolerance), 0.0, 1e-3,
                   "relative accuracy of the QPs of every stage but the last")
                   .Alias("relax_and_fix_stage_tolerance").Advanced());
  t->push_back(Opt("relax_and_fix.stage_rounding", in(&R::stage_rounding),
                   "run the search's rounding heuristic inside the stages")
                   .Alias("relax_and_fix_stage_rounding").Advanced());
  t->push_back(Opt("relax_and_fix.after_nodes", in(&R::after_nodes), 0, 100000000,
                   "a window whose root roundings gave a plan is seeded only once its search has processed this many "
                   "nodes without ending (0: at the root)")
                   .Advanced());
  t->push_back(Opt("relax_and_fix.wait_gap", in(&R::wait_gap), 0.0, 1e9,
                   "... and only when the root's plan is within this relative gap of the root bound (a poorer plan "
                   "is seeded at once)")
                   .Advanced());
  t->push_back(Opt("relax_and_fix.first_plan_dive", in(&R::first_plan_dive),
                   "a seeded window whose root roundings find no plan first gets one from a one-node-per-stage dive")
                   .Advanced());
  t->push_back(Opt("relax_and_fix.rounding_dive", in(&R::rounding_dive),
                   "the first-plan dive rounds each configuration from the previous stage's completion, one QP per "
                   "stage, before the stage-search dive")
                   .Advanced());
}

void AddPolishKeys(Table* t) {
  using O = PolishOptions;
  auto in = [](auto O::*field) { return In(&P::polish, field); };
  t->push_back(Opt("polish.enabled", in(&O::enabled),
                   "solve each window's plan again with exact sin/cos and its integer choices fixed")
                   .Alias("polish"));
  t->push_back(Opt("polish.time_limit", in(&O::time_limit_s), 1e-4, 3600, "time of the polisher per window")
                   .Alias("polish_time_limit").Unit("s"));
  t->push_back(Opt("polish.reserve_fraction", in(&O::reserve_fraction), 0.0, 0.5,
                   "fraction of the plan's time limit kept from every window's search for the polisher "
                   "(at most polish.time_limit, at most half the time left)")
                   .Advanced());
  t->push_back(Opt("polish.sequential_qp", in(&O::sequential_qp),
                   "polish by sequential QP on mfp's interior point first").Alias("polish_sequential_qp").Advanced());
  t->push_back(Opt("polish.slsqp_fallback", in(&O::slsqp_fallback),
                   "NLopt's SLSQP when the sequential QP ends outside the constraints (or alone)")
                   .Alias("polish_slsqp_fallback").Advanced());
  t->push_back(Opt("polish.replan_inexact", in(&O::replan_when_inexact),
                   "a window the polisher cannot make exact is planned again with boxes shrunk by the chords' error")
                   .Alias("polish_replan_inexact").Advanced());
  t->push_back(Opt("polish.completion_overrun", in(&O::completion_overrun_s), 0, 10,
                   "a re-plan out of time completes the window's own choices with one QP, at most this long past the "
                   "plan's deadline; a window's search without a plan finishes its roundings and first-plan dive at "
                   "most this long past its deadline; the polisher of the plan's first window gets at least this long "
                   "when the plan's time is spent").Unit("s").Advanced());
}

Table MakeTable() {
  Table t;
  AddPlanKeys(&t);
  AddWindowKeys(&t);
  AddRouteKeys(&t);
  AddSolverKeys(&t);
  AddFormulationKeys(&t);
  AddSearchKeys(&t);
  AddRelaxAndFixKeys(&t);
  AddPolishKeys(&t);
  return t;
}

}  // namespace

const OptionTable<PlannerOptions>& PlannerOptionTable() {
  static const Table table = MakeTable();
  return table;
}

namespace {

// Members of RelaxAndFixOptions the planner sets itself for each window (footstep_planner.cc):
// a key for them would be replaced silently, so each is refused naming the key that wins.
void RejectPlannerSetRelaxAndFixKeys(const YAML::Node& node, const YamlContext& ctx) {
  const YAML::Node rf = node.IsMap() ? node["relax_and_fix"] : YAML::Node(YAML::NodeType::Undefined);
  if (!rf || !rf.IsMap()) return;
  const std::pair<const char*, const char*> kSetByPlanner[] = {
      {"time_limit", "planner.relax_and_fix.time_share (of the window's time)"},
      {"stage", "planner.search (the stages search with the window's search options)"}};
  for (const auto& [key, winner] : kSetByPlanner) {
    if (rf[key]) {
      throw InputError(ctx.Child("relax_and_fix").Child(key).Where() + ": set by the planner from " + winner +
                       ", which wins: write that");
    }
  }
}

}  // namespace

std::vector<std::string> ReadPlannerOptions(const YAML::Node& node, const YamlContext& ctx,
                                            PlannerOptions* options) {
  RejectPlannerSetRelaxAndFixKeys(node, ctx);
  return ReadOptions(PlannerOptionTable(), node, ctx, options);
}

std::vector<OptionDoc> PlannerOptionDocs(const std::string& prefix) {
  return DocumentOptions(PlannerOptionTable(), prefix, PlannerOptions{});
}

}  // namespace mfp
