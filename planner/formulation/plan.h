#pragma once
// The result of planning: footsteps plus the solver's account of how it got them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "base/solve_status.h"
#include "geometry/convex_region.h"

namespace mfp {

struct Footstep {
  int index = 0;                                            // position in the plan
  int leg = 0;                                              // index into RobotModel::legs
  Eigen::Vector3d position_world_m = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;                                     // body yaw of the configuration
  int region_id = -1;                                       // ConvexRegion::id it stands in
};

// One window's account (PlanFootsteps fills one per MIQP solved, retries included): what
// entered its MIQP and where its time went. For benchmarks and logs.
struct WindowRecord {
  int new_steps = 0;          // footsteps the window plans
  int regions = 0;            // regions in its MIQP
  int integer_variables = 0;  // binaries of its MIQP
  SolveStatus status = SolveStatus::kInternalError;  // the window's search result
  int nodes = 0;
  int relaxations = 0;        // QPs solved: the search's and its root heuristics'
  int heuristic_relaxations = 0;  // of them, the root heuristics' (relax-and-fix's dives and seed)
  int fallbacks = 0;          // of them, solved by the solver's fallback (the search's and its root heuristics')
  int kept_steps = 0;          // steps accepted from it (0 on a failure or a retry)
  double time_limit_s = 0.0;   // the search's share of the plan's time
  double build_s = 0.0;        // formulating the MIQP
  double heuristic_s = 0.0;    // relax-and-fix seeding (inside the search's root)
  double search_s = 0.0;       // the whole search, heuristics included
  double polish_s = 0.0;       // exact-trigonometry polish
  bool polished = false;       // the polished steps replaced the MIQP's
  bool replanned = false;      // planned again within the chords' error (exact_window.h)
  // The client's previous plan (PlanRequest::warm_start): the start stance stood on one,
  // its search was bounded by replan_time_s, and that bounded search found no plan so the
  // full search ran after it. First window only.
  bool warm_matched = false;
  bool bounded_replan = false;
  bool replan_fell_back = false;
};

// A gap in the regions on a leg's nominal path ahead of a stopped plan's last stance: the
// last point of the path on a region before it and the first one after it [m, world].
struct PlanStopGap {
  bool found = false;
  bool examined = true;           // false: the deadline came before the whole way ahead was examined
  int leg = -1;                   // index into RobotModel::legs
  int from_region = -1;           // ConvexRegion::id before the gap
  int to_region = -1;             // ... after it; -1: no region on the rest of the path
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
  // Between the two regions' polygons, the larger of the x and y distances (a step moves a
  // foot at most step_span_m on each world axis), and the height change at the two points [m].
  double width_m = 0.0;
  double rise_m = 0.0;
  double step_span_m = 0.0;       // the most one step moves a foot on one axis: d_lim + l_bnd [m]
  // No step crosses it straight on: width_m > step_span_m, |rise_m| > dz_max, or no region
  // after it.
  bool blocks = false;
  // When it blocks: the first region of a chain of steps (each within step_span_m and
  // dz_max) from the region before it to the one after it through regions near it, the
  // way one foot could go round it (a whole stance may still not fit there); -1: none.
  int detour_region = -1;
  Eigen::Vector2d detour_m = Eigen::Vector2d::Zero();  // a vertex of that region [m, world]
};

// Where a plan that stops short of the goal (status partial) stopped and why.
struct PlanStop {
  bool stopped = false;
  Eigen::Vector3d centre_world_m = Eigen::Vector3d::Zero();  // the last stance's centre (mean foot)
  double yaw_rad = 0.0;                                       // its body yaw
  std::vector<int> regions;       // the ids of the regions its feet stand on
  std::string reason;             // why the windows ended (the message's reason, short)
  PlanStopGap gap;                // the first gap ahead that no step spans, else the widest
};

struct Plan {
  SolveStatus status = SolveStatus::kInternalError;
  std::string message;        // human-readable detail for non-optimal outcomes
  bool reaches_goal = false;  // final stance within the goal tolerances
  double objective = 0.0;     // sum over windows of each MIQP's objective (incl. constants)
  double bound = 0.0;         // sum of the windows' best lower bounds
  double gap = 0.0;           // relative gap (objective - bound) / max(1, |objective|)
  double objective_offset = 0.0;  // constant terms: objective = MPS objective + offset (first window)
  double solve_time_s = 0.0;
  double setup_s = 0.0;        // request checks, reachable regions and route, before the first window
  int nodes = 0;               // branch-and-bound nodes over all windows
  int relaxations = 0;         // continuous QPs solved over all windows
  int relaxation_fallbacks = 0;  // of the searches' and their root heuristics' QPs, those solved by the solver's fallback
  int integer_variables = 0;   // in the first window's MIQP
  int windows = 0;
  int horizon_retries = 0;     // windows planned again: a longer horizon, a closer local goal, clear of the body
  // footsteps[0 .. n-1] are the start stance (in gait order); the last n are the final
  // stance, one per leg.
  std::vector<Footstep> footsteps;
  std::vector<WindowRecord> window_records;  // one per window solved, in order
  // The goal pose the plan aimed for and reaches_goal is judged against: the request's,
  // or, when goal_moved, the nearest certified stance within the planner's goal position
  // and heading tolerances (a requested goal foot spot lay on no region) [m, rad].
  bool goal_moved = false;
  double goal_x_m = 0.0, goal_y_m = 0.0, goal_yaw_rad = 0.0;
  // Goal footholds on seen floor the plan stands on besides the caller's regions (ids above
  // theirs; planner/planning/internal/goal_footholds.h); plan validation counts them as regions.
  std::vector<ConvexRegion> footholds;
  // A partial plan's stop: its last stance and the gap ahead (stopped = false otherwise).
  PlanStop stop;
};

}  // namespace mfp
