#include "planner/planner_options_yaml.h"

#include <cmath>

#include "planner/check.h"

namespace mfp {

void ReadPlannerOptions(const YAML::Node& node, const YamlContext& ctx, PlannerOptions* options) {
  RejectUnknownKeys(node, ctx,
                    {"max_steps", "window", "time_limit", "goal_tolerance", "goal_yaw_tolerance",
                     "start_tolerance", "yaw_segment", "yaw_margin", "region_encoding", "yaw_encoding",
                     "prune_unreachable_regions", "monotone_trimming", "max_nodes", "relative_gap",
                     "node_selection", "branching", "rounding_frequency", "relaxation_solver",
                     "bound_propagation", "rounding_heuristic", "plunge_fraction", "reliability",
                     "strong_branching_candidates", "strong_branching_lookahead", "threads", "clip_yaw_to_reach",
                     "reduced_cost_fixing", "early_cutoff", "relax_and_fix", "relax_and_fix_time_share",
                     "relax_and_fix_min_configurations", "relax_and_fix_region_hull",
                     "relax_and_fix_stage_tolerance", "snap_yaw_segments",
                     "relax_and_fix_two_paths", "relax_and_fix_stage_rounding", "route_guidance",
                     "local_goal_lookahead", "max_horizon_windows"});
  PlannerOptions& o = *options;
  o.default_max_steps = OptionalInt(node, ctx, "max_steps", 1, 100000).value_or(o.default_max_steps);
  o.threads = OptionalInt(node, ctx, "threads", 1, 64).value_or(o.threads);
  o.relax_and_fix = OptionalBool(node, ctx, "relax_and_fix").value_or(o.relax_and_fix);
  o.relax_and_fix_time_share =
      OptionalDouble(node, ctx, "relax_and_fix_time_share", 0.01, 1).value_or(o.relax_and_fix_time_share);
  o.relax_and_fix_min_configurations =
      OptionalInt(node, ctx, "relax_and_fix_min_configurations", 2, 100000)
          .value_or(o.relax_and_fix_min_configurations);
  o.relax_and_fix_region_hull =
      OptionalBool(node, ctx, "relax_and_fix_region_hull").value_or(o.relax_and_fix_region_hull);
  o.relax_and_fix_two_paths = OptionalBool(node, ctx, "relax_and_fix_two_paths").value_or(o.relax_and_fix_two_paths);
  o.relax_and_fix_stage_rounding =
      OptionalBool(node, ctx, "relax_and_fix_stage_rounding").value_or(o.relax_and_fix_stage_rounding);
  o.route_guidance = OptionalBool(node, ctx, "route_guidance").value_or(o.route_guidance);
  o.local_goal_lookahead_m =
      OptionalDouble(node, ctx, "local_goal_lookahead", -1.0, 1000.0).value_or(o.local_goal_lookahead_m);
  o.max_horizon_windows = OptionalInt(node, ctx, "max_horizon_windows", 1, 100).value_or(o.max_horizon_windows);
  o.snap_yaw_segments = OptionalBool(node, ctx, "snap_yaw_segments").value_or(o.snap_yaw_segments);
  o.relax_and_fix_stage_tolerance = OptionalDouble(node, ctx, "relax_and_fix_stage_tolerance", 0.0, 1e-3)
                                        .value_or(o.relax_and_fix_stage_tolerance);
  o.default_window_steps = OptionalInt(node, ctx, "window", 1, 1000).value_or(o.default_window_steps);
  o.default_time_limit_s = OptionalDouble(node, ctx, "time_limit", 1e-3, 3600).value_or(o.default_time_limit_s);
  o.goal_tolerance_m = OptionalDouble(node, ctx, "goal_tolerance", 1e-4, 10).value_or(o.goal_tolerance_m);
  o.goal_yaw_tolerance_rad =
      OptionalDouble(node, ctx, "goal_yaw_tolerance", 1e-4, M_PI).value_or(o.goal_yaw_tolerance_rad);
  o.start_tolerance_m = OptionalDouble(node, ctx, "start_tolerance", 0, 1).value_or(o.start_tolerance_m);
  if (const auto backend = OptionalString(node, ctx, "relaxation_solver")) {
    try {
      o.relaxation_solver = ParseRelaxationBackend(*backend);
    } catch (const InputError& e) {
      throw InputError(ctx.Child("relaxation_solver").Where() + ": " + e.what());
    }
  }
  FormulationOptions& f = o.formulation;
  f.yaw_segment_rad = OptionalDouble(node, ctx, "yaw_segment", 0.02, M_PI).value_or(f.yaw_segment_rad);
  f.yaw_margin_rad = OptionalDouble(node, ctx, "yaw_margin", 0, M_PI).value_or(f.yaw_margin_rad);
  if (const auto enc = OptionalString(node, ctx, "region_encoding")) {
    if (*enc == "big_m") {
      f.region_encoding = RegionEncoding::kBigM;
    } else if (*enc == "convex_hull") {
      f.region_encoding = RegionEncoding::kConvexHull;
    } else {
      throw InputError(ctx.Child("region_encoding").Where() + ": '" + *enc +
                       "' is not one of big_m, convex_hull");
    }
  }
  if (const auto enc = OptionalString(node, ctx, "yaw_encoding")) {
    if (*enc == "big_m") {
      f.yaw_encoding = YawEncoding::kBigM;
    } else if (*enc == "convex_hull") {
      f.yaw_encoding = YawEncoding::kConvexHull;
    } else {
      throw InputError(ctx.Child("yaw_encoding").Where() + ": '" + *enc + "' is not one of big_m, convex_hull");
    }
  }
  f.prune_unreachable_regions =
      OptionalBool(node, ctx, "prune_unreachable_regions").value_or(f.prune_unreachable_regions);
  f.monotone_trimming = OptionalBool(node, ctx, "monotone_trimming").value_or(f.monotone_trimming);
  f.clip_yaw_to_reach = OptionalBool(node, ctx, "clip_yaw_to_reach").value_or(f.clip_yaw_to_reach);
  BranchAndBoundOptions& b = o.branch_and_bound;
  b.max_nodes = OptionalInt(node, ctx, "max_nodes", 1, 10000000).value_or(b.max_nodes);
  b.relative_gap = OptionalDouble(node, ctx, "relative_gap", 0, 1).value_or(b.relative_gap);
  b.rounding_frequency = OptionalInt(node, ctx, "rounding_frequency", 0, 1000000).value_or(b.rounding_frequency);
  b.bound_propagation = OptionalBool(node, ctx, "bound_propagation").value_or(b.bound_propagation);
  b.reduced_cost_fixing = OptionalBool(node, ctx, "reduced_cost_fixing").value_or(b.reduced_cost_fixing);
  b.early_cutoff = OptionalBool(node, ctx, "early_cutoff").value_or(b.early_cutoff);
  b.rounding_heuristic = OptionalBool(node, ctx, "rounding_heuristic").value_or(b.rounding_heuristic);
  b.plunge_fraction = OptionalDouble(node, ctx, "plunge_fraction", 0, 1).value_or(b.plunge_fraction);
  b.reliability = OptionalInt(node, ctx, "reliability", 0, 1000).value_or(b.reliability);
  b.strong_branching_candidates =
      OptionalInt(node, ctx, "strong_branching_candidates", 0, 10000).value_or(b.strong_branching_candidates);
  b.strong_branching_lookahead =
      OptionalInt(node, ctx, "strong_branching_lookahead", 1, 10000).value_or(b.strong_branching_lookahead);
  if (const auto sel = OptionalString(node, ctx, "node_selection")) {
    if (*sel == "best_bound") {
      b.node_selection = NodeSelection::kBestBound;
    } else if (*sel == "depth_first") {
      b.node_selection = NodeSelection::kDepthFirst;
    } else if (*sel == "dive_then_best_bound") {
      b.node_selection = NodeSelection::kDiveThenBestBound;
    } else if (*sel == "plunging") {
      b.node_selection = NodeSelection::kBestBoundWithPlunging;
    } else {
      throw InputError(ctx.Child("node_selection").Where() + ": '" + *sel +
                       "' is not one of best_bound, depth_first, dive_then_best_bound, plunging");
    }
  }
  if (const auto br = OptionalString(node, ctx, "branching")) {
    if (*br == "most_fractional") {
      b.branching = BranchingRule::kMostFractional;
    } else if (*br == "sos1") {
      b.branching = BranchingRule::kSos1Split;
    } else if (*br == "group_order") {
      b.branching = BranchingRule::kGroupOrder;
    } else if (*br == "reliability") {
      b.branching = BranchingRule::kReliability;
    } else {
      throw InputError(ctx.Child("branching").Where() + ": '" + *br +
                       "' is not one of most_fractional, sos1, group_order, reliability");
    }
  }
}

}  // namespace mfp
