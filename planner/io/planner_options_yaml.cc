#include "planner/io/planner_options_yaml.h"

#include <cmath>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "planner/base/check.h"

namespace mfp {
namespace {

// One key of the `planner:` section: the member of struct S it sets and its range.
template <class S>
struct Field {
  const char* key;
  std::variant<int S::*, double S::*, bool S::*> member;
  double min = 0.0, max = 0.0;  // ignored for bool
};

// One key naming an enum value: the member of struct S it sets and the names it takes.
template <class S, class E>
struct EnumField {
  const char* key;
  E S::*member;
  std::vector<std::pair<const char*, E>> names;
};

// Each struct's keys, named once: they drive both the unknown-key check and the reading.
const std::vector<Field<PlannerOptions>> kPlannerFields = {
    {"max_steps", &PlannerOptions::default_max_steps, 1, 100000},
    {"window", &PlannerOptions::default_window_steps, 1, 1000},
    {"time_limit", &PlannerOptions::default_time_limit_s, 1e-3, 3600},
    {"goal_tolerance", &PlannerOptions::goal_tolerance_m, 1e-4, 10},
    {"goal_yaw_tolerance", &PlannerOptions::goal_yaw_tolerance_rad, 1e-4, M_PI},
    {"start_tolerance", &PlannerOptions::start_tolerance_m, 0, 1},
    {"snap_yaw_segments", &PlannerOptions::snap_yaw_segments},
    {"route_guidance", &PlannerOptions::route_guidance},
    {"local_goal_lookahead", &PlannerOptions::local_goal_lookahead_m, -1.0, 1000.0},
    {"local_goal_detour_ratio", &PlannerOptions::local_goal_detour_ratio, 1.0, 100.0},
    {"stance_route", &PlannerOptions::stance_route},
    {"route_proposals", &PlannerOptions::route_proposals},
    {"max_horizon_windows", &PlannerOptions::max_horizon_windows, 1, 100},
    {"window_time_slack", &PlannerOptions::window_time_slack, 0.0, 1000.0},
    {"window_stall_fraction", &PlannerOptions::window_stall_fraction, 0.0, 1.0},
    {"route_step_budget", &PlannerOptions::route_step_budget, 1.0, 1000.0},
    {"anytime_windows", &PlannerOptions::anytime_windows},
    {"anytime_window_cap", &PlannerOptions::anytime_window_cap, 1.0, 1000.0},
    {"warm_start_match", &PlannerOptions::warm_start_match_m, 0, 1},
    {"replan_time", &PlannerOptions::replan_time_s, 0, 3600},
};

const std::vector<Field<RelaxationSolverOptions>> kSolverFields = {
    {"threads", &RelaxationSolverOptions::threads, 1, 64},
};

const std::vector<Field<FormulationOptions>> kFormulationFields = {
    {"yaw_segment", &FormulationOptions::yaw_segment_rad, 0.02, M_PI},
    {"yaw_margin", &FormulationOptions::yaw_margin_rad, 0, M_PI},
    {"prune_unreachable_regions", &FormulationOptions::prune_unreachable_regions},
    {"monotone_trimming", &FormulationOptions::monotone_trimming},
    {"clip_yaw_to_reach", &FormulationOptions::clip_yaw_to_reach},
    {"trimmed_configurations_hold_yaw", &FormulationOptions::trimmed_configurations_hold_yaw},
};

const std::vector<Field<BranchAndBoundOptions>> kSearchFields = {
    {"max_nodes", &BranchAndBoundOptions::max_nodes, 1, 10000000},
    {"relative_gap", &BranchAndBoundOptions::relative_gap, 0, 1},
    {"rounding_frequency", &BranchAndBoundOptions::rounding_frequency, 0, 1000000},
    {"bound_propagation", &BranchAndBoundOptions::bound_propagation},
    {"reduced_cost_fixing", &BranchAndBoundOptions::reduced_cost_fixing},
    {"early_cutoff", &BranchAndBoundOptions::early_cutoff},
    {"rounding_heuristic", &BranchAndBoundOptions::rounding_heuristic},
    {"plunge_fraction", &BranchAndBoundOptions::plunge_fraction, 0, 1},
    {"reliability", &BranchAndBoundOptions::reliability, 0, 1000},
    {"strong_branching_candidates", &BranchAndBoundOptions::strong_branching_candidates, 0, 10000},
    {"strong_branching_lookahead", &BranchAndBoundOptions::strong_branching_lookahead, 1, 10000},
};

const std::vector<Field<PolishOptions>> kPolishFields = {
    {"polish", &PolishOptions::enabled},
    {"polish_time_limit", &PolishOptions::time_limit_s, 1e-4, 3600},
    {"polish_sequential_qp", &PolishOptions::sequential_qp},
    {"polish_slsqp_fallback", &PolishOptions::slsqp_fallback},
    {"polish_replan_inexact", &PolishOptions::replan_when_inexact},
};

// Flat keys with the relax_and_fix prefix, as scenario files have always named them.
const std::vector<Field<RelaxAndFixOptions>> kRelaxAndFixFields = {
    {"relax_and_fix", &RelaxAndFixOptions::enabled},
    {"relax_and_fix_time_share", &RelaxAndFixOptions::time_share, 0.01, 1},
    {"relax_and_fix_min_configurations", &RelaxAndFixOptions::min_configurations, 2, 100000},
    {"relax_and_fix_region_hull", &RelaxAndFixOptions::hull_for_later_steps},
    {"relax_and_fix_two_paths", &RelaxAndFixOptions::two_paths},
    {"relax_and_fix_stage_tolerance", &RelaxAndFixOptions::stage_relaxation_tolerance, 0.0, 1e-3},
    {"relax_and_fix_stage_rounding", &RelaxAndFixOptions::stage_rounding},
};

const EnumField<FormulationOptions, RegionEncoding> kRegionEncoding = {
    "region_encoding", &FormulationOptions::region_encoding,
    {{"big_m", RegionEncoding::kBigM}, {"convex_hull", RegionEncoding::kConvexHull}}};
const EnumField<FormulationOptions, YawEncoding> kYawEncoding = {
    "yaw_encoding", &FormulationOptions::yaw_encoding,
    {{"big_m", YawEncoding::kBigM}, {"convex_hull", YawEncoding::kConvexHull}}};
const EnumField<BranchAndBoundOptions, NodeSelection> kNodeSelection = {
    "node_selection", &BranchAndBoundOptions::node_selection,
    {{"best_bound", NodeSelection::kBestBound},
     {"depth_first", NodeSelection::kDepthFirst},
     {"dive_then_best_bound", NodeSelection::kDiveThenBestBound},
     {"plunging", NodeSelection::kBestBoundWithPlunging}}};
const EnumField<BranchAndBoundOptions, BranchingRule> kBranching = {
    "branching", &BranchAndBoundOptions::branching,
    {{"most_fractional", BranchingRule::kMostFractional},
     {"sos1", BranchingRule::kSos1Split},
     {"group_order", BranchingRule::kGroupOrder},
     {"reliability", BranchingRule::kReliability}}};
constexpr const char* kRelaxationSolverKey = "relaxation_solver";
// Route proposals: the yaw rate as a flat key, the speeds as a list of fractions of d_lim.
const std::vector<Field<RouteProposalOptions>> kRouteProposalFields = {
    {"route_proposal_yaw_rate", &RouteProposalOptions::yaw_rate_fraction, 0.0, 1.0},
};
constexpr const char* kRouteProposalSpeedsKey = "route_proposal_speeds";

template <class S>
void AddKeys(const std::vector<Field<S>>& fields, std::vector<std::string>* keys) {
  for (const Field<S>& f : fields) keys->push_back(f.key);
}

template <class S>
void ReadFields(const YAML::Node& node, const YamlContext& ctx, const std::vector<Field<S>>& fields, S* s) {
  for (const Field<S>& f : fields) {
    if (const auto* m = std::get_if<int S::*>(&f.member)) {
      s->**m = OptionalInt(node, ctx, f.key, static_cast<int>(f.min), static_cast<int>(f.max)).value_or(s->**m);
    } else if (const auto* m = std::get_if<double S::*>(&f.member)) {
      s->**m = OptionalDouble(node, ctx, f.key, f.min, f.max).value_or(s->**m);
    } else if (const auto* m = std::get_if<bool S::*>(&f.member)) {
      s->**m = OptionalBool(node, ctx, f.key).value_or(s->**m);
    }
  }
}

template <class S, class E>
void ReadEnum(const YAML::Node& node, const YamlContext& ctx, const EnumField<S, E>& field, S* s) {
  const auto name = OptionalString(node, ctx, field.key);
  if (!name) return;
  std::string allowed;
  for (const auto& [text, value] : field.names) {
    if (*name == text) {
      s->*field.member = value;
      return;
    }
    allowed += (allowed.empty() ? "" : ", ") + std::string(text);
  }
  throw InputError(ctx.Child(field.key).Where() + ": '" + *name + "' is not one of " + allowed);
}

}  // namespace

void ReadPlannerOptions(const YAML::Node& node, const YamlContext& ctx, PlannerOptions* options) {
  std::vector<std::string> keys;
  AddKeys(kPlannerFields, &keys);
  AddKeys(kSolverFields, &keys);
  AddKeys(kFormulationFields, &keys);
  AddKeys(kSearchFields, &keys);
  AddKeys(kRelaxAndFixFields, &keys);
  AddKeys(kPolishFields, &keys);
  AddKeys(kRouteProposalFields, &keys);
  keys.push_back(kRouteProposalSpeedsKey);
  for (const char* key : {kRegionEncoding.key, kYawEncoding.key, kNodeSelection.key, kBranching.key}) keys.push_back(key);
  keys.push_back(kRelaxationSolverKey);
  RejectUnknownKeys(node, ctx, keys);

  PlannerOptions& o = *options;
  ReadFields(node, ctx, kPlannerFields, &o);
  ReadFields(node, ctx, kSolverFields, &o.solvers);
  ReadFields(node, ctx, kFormulationFields, &o.formulation);
  ReadFields(node, ctx, kSearchFields, &o.branch_and_bound);
  ReadFields(node, ctx, kRelaxAndFixFields, &o.relax_and_fix);
  ReadFields(node, ctx, kPolishFields, &o.polish);
  ReadFields(node, ctx, kRouteProposalFields, &o.route_proposal);
  if (node[kRouteProposalSpeedsKey]) {
    const YamlContext speeds_ctx = ctx.Child(kRouteProposalSpeedsKey);
    std::vector<double> speeds = ReadNumbers(node[kRouteProposalSpeedsKey], speeds_ctx, -1);
    for (double v : speeds) {
      if (!(v > 0.0 && v <= 2.0)) {
        throw InputError(speeds_ctx.Where() + ": each speed is a fraction of d_lim in (0, 2], got " + std::to_string(v));
      }
    }
    o.route_proposal.advance_fractions = std::move(speeds);
  }
  ReadEnum(node, ctx, kRegionEncoding, &o.formulation);
  ReadEnum(node, ctx, kYawEncoding, &o.formulation);
  ReadEnum(node, ctx, kNodeSelection, &o.branch_and_bound);
  ReadEnum(node, ctx, kBranching, &o.branch_and_bound);
  if (const auto backend = OptionalString(node, ctx, kRelaxationSolverKey)) {
    try {
      o.solvers.backend = ParseRelaxationBackend(*backend);
    } catch (const InputError& e) {
      throw InputError(ctx.Child(kRelaxationSolverKey).Where() + ": " + e.what());
    }
  }
}

}  // namespace mfp
