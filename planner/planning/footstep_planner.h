#pragma once
// One entry point for planning: robot + regions + request + options -> Plan.
// Chains receding windows of MIQPs (the paper plans 4n steps at a time) until the goal
// is reached, max_steps are spent, or the time limit runs out. No I/O.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "base/deadline.h"
#include "geometry/convex_region.h"
#include "geometry/seen_surface.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"
#include "planner/planning/internal/relax_and_fix.h"
#include "planner/planning/internal/route_proposals.h"
#include "planner/planning/internal/stance_route.h"
#include "planner/planning/internal/window_polisher.h"
#include "planner/qp/relaxation_solver.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/robot/body_clearance.h"
#include "planner/robot/robot_model.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

struct PlanRequest {
  // Current feet in the robot's leg order (RobotModel::legs), world frame [m].
  std::vector<Eigen::Vector3d> start_feet_world_m;
  double start_yaw_rad = 0.0;  // body yaw of the start stance [rad]
  double goal_x_m = 0.0;       // goal body position (centre of contacts) [m]
  double goal_y_m = 0.0;
  double goal_yaw_rad = 0.0;
  int max_steps = 0;       // new footsteps in the whole plan; 0 = PlannerOptions default
  int window_steps = 0;    // new footsteps per MIQP; 0 = PlannerOptions default (2 n)
  double time_limit_s = 0; // whole plan; 0 = PlannerOptions default
  // The caller's deadline, and its stop flag (default: none): the plan ends at the sooner
  // of it and time_limit_s, checked inside every relaxation solve; the best plan so far is
  // returned with status time_limit. A daemon passes the request's arrival + its limit
  // (queue time counts) and a flag that SIGTERM or a superseding request sets.
  Deadline deadline;
  int max_windows = 0;     // MIQPs solved at most; 0 = as many as the route needs. 1 = exactly
                           // the single MIQP of FirstWindowProblem (benchmarks of Table I)
  // Optional: the footsteps of this client's previous plans (Plan::footsteps, newest
  // first) on the same map. When the start stance lies on one, its steps ahead seed the
  // first window's search (planner/planning/internal/warm_start.h), and
  // PlannerOptions::replan_time bounds that search.
  std::vector<std::vector<Footstep>> warm_start;
  // Optional: called after each accepted window with the plan so far (every step in it
  // valid; status partial unless it reaches the goal), so a caller whose deadline comes
  // first (a daemon's watchdog) can answer with it. Called on the planning thread.
  std::function<void(const Plan&)> on_plan_so_far;
  // Optional: the occupied space the body must keep clear of (a box terrain's boxes, a
  // map's occupied columns), as prisms in the world frame. With a known body box
  // (RobotModel::body) the stance route keeps the body's plan box out of every prism in
  // its height band, turning where a passage fits only one way, and the windows follow
  // that route and its yaws. Empty (the default): no body check, plans as before.
  std::vector<BodyObstacle> body_obstacles;
  // Optional: the surface the map's sensor saw from above (the layers or faces the regions
  // came from). A start foot on it within PlannerOptions::start_tolerance_m is accepted
  // where no region holds it (the robot stands there; its first step lands in a region).
  // Shared, not copied: a map's layers are large and every request on the map reads them.
  // Null or empty (the default): every start foot must be on a region.
  std::shared_ptr<const SeenSurface> seen_surface;
};

struct PlannerOptions {
  int default_max_steps = 0;        // 0 = 12 n
  // 0 = 2 n. The paper plans 4 n steps per MIQP; with this solver windows of two
  // configurations reach every scenario goal with each window proven optimal, in a
  // fraction of the time of 4 n windows, which end at their time limits (docs/measurements.md).
  int default_window_steps = 0;
  double default_time_limit_s = 30.0;
  double goal_tolerance_m = 0.05;        // every final foot within this of its goal spot
  double goal_yaw_tolerance_rad = 0.15;  // final body yaw within this of the goal yaw
  double start_tolerance_m = 0.02;       // a start foot may be this far off its region
  // A goal stance with a foot spot on no region (route guidance only) is moved to the
  // nearest stance whose spots all lie on regions, at most this far [m] and this much
  // turned [rad]; beyond them the request ends invalid_goal (planner/planning/internal/goal.h).
  double goal_position_tolerance_m = 0.3;
  double goal_heading_tolerance_rad = 0.2;
  // The grid of that search: poses goal_search_step_m apart and turns
  // goal_search_yaw_step_rad apart within the tolerances; beyond them, only to name the
  // nearest certified stance in the invalid_goal message, poses goal_report_step_m apart
  // out to goal_report_radius_m (turns: the heading tolerance either way) [m, rad].
  double goal_search_step_m = 0.02;
  double goal_search_yaw_step_rad = 0.05;
  double goal_report_step_m = 0.05;
  double goal_report_radius_m = 2.0;
  // A plan that stops short of the goal names the first gap ahead (Plan::stop,
  // planner/planning/internal/stop_report.h), found by sampling the way ahead
  // stop_report_step_l_bnd times l_bnd apart (at least 1 mm; a gap narrower than a
  // quarter of l_bnd lies within every reference box), with at most
  // stop_report_max_samples samples, which bound the report's work and memory on a far
  // goal: a longer way is sampled more sparsely (20000 x 0.25 l_bnd is 0.4 km for the
  // hexapod), and a gap narrower than its samples' spacing may go unnamed.
  double stop_report_step_l_bnd = 0.25;
  int stop_report_max_samples = 20000;
  // When no stance on regions lies within those tolerances, a stance whose spots off the
  // regions each stand on seen floor (PlanRequest::seen_surface: a disk of the foot
  // radius, this margin and one map cell, flat within a cell) is planned to instead,
  // each such spot given a foothold region (planner/planning/internal/goal_footholds.h).
  bool goal_seen_footholds = true;
  double goal_foothold_margin_m = 0.01;
  // A foothold is a square about its spot: its first half side (0: half goal_tolerance_m,
  // so a final foot within the goal tolerance of its spot stays on it), doubled while its
  // disk stays flat up to the largest half side (0: the robot's d_lim, a larger foothold
  // also holding the steps up to the stance) [m].
  double goal_foothold_half_side_m = 0.0;
  double goal_foothold_max_half_side_m = 0.0;
  // A start foot on no region but on flat seen floor (the same disk) gets a foothold too,
  // which the first steps may use (StartFootholds in goal_footholds.h).
  bool start_seen_footholds = true;
  // Region extraction for this robot keeps surfaces with the stance height plus this much
  // free space above them (RegionExtractorOptions::clearance_m) [m].
  double body_clearance_margin_m = 0.1;
  // On an occupancy map, PlanRequest::body_obstacles are the map's occupied voxels that
  // may reach the body's band (terrain/extraction/map_body_obstacles.h), when the robot's
  // body is known. The callers that read a map fill them; PlanFootsteps does not read it.
  bool map_body_obstacles = true;
  // Which relaxation solvers and how many workers. PlanFootsteps does not read it: callers
  // make the solvers from it (MakeRelaxationSolvers) and pass them in; it rides here so
  // that one `planner:` block configures a whole plan.
  RelaxationSolverOptions solvers;
  // A relaxed yaw that one segment alone represents (on a breakpoint, as the goal yaw
  // is) is set to that segment before branching (MiqpFormulation::SnapYawToOneSegment).
  bool snap_yaw_segments = true;
  // Route guidance (planner/route_guide.h): before the windows, a graph over the regions
  // answers 'no route' (SolveStatus::kNoRoute) when it does not connect start and goal,
  // and the route's length sets the default step budget. Only for whole plans
  // (PlanRequest::max_windows == 0).
  bool route_guidance = true;
  // Each window's goal term follows the route: a local goal this many metres of route
  // ahead of the current stance (0: the goal itself; negative: about one window's walk,
  // 2 d_lim on a stance route, else twice the largest nominal foot distance L_leg), while
  // the route left is longer than local_goal_detour_ratio times the straight line to the
  // goal. 1 (default): wherever the route bends at all. Larger values let the goal itself
  // pull on nearly straight routes, but near a turn that pull cuts the corner: on an
  // L-shaped field the windows stalled at the inner corner (docs/measurements.md).
  double local_goal_lookahead_m = -1.0;
  double local_goal_detour_ratio = 1.0;
  // The route the local goals follow comes from a search over stance poses where every
  // leg's reference box meets a region (planner/planning/internal/stance_route.h), not from the
  // region graph's centres, which cut corners a whole body cannot. The region graph
  // still decides 'no route'; where the stance search finds nothing its route is kept.
  bool stance_route = true;
  // That search's grid, headings, costs and the body's margin (StanceRouteOptions).
  StanceRouteOptions stance_search;
  // Each guided window's search starts from plans that walk the route at a few speeds
  // (planner/planning/internal/route_proposals.h), solved as QPs with their regions fixed.
  bool route_proposals = true;
  RouteProposalOptions route_proposal;
  // Default step budget under route guidance (no max_steps given): configurations for
  // this many times the route's length at d_lim each. On uneven fields windows advance
  // 0.3-0.6 d_lim per configuration: 3 ended zoo quadrupeds' plans 1.7 m short.
  double route_step_budget = 6.0;
  // Adaptive horizons: a failed window is planned again, backing up one window, with up
  // to this many times the default window's steps (1: no retries). Only with route guidance.
  int max_horizon_windows = 2;
  // Progress, not budget: a plan whose way left (the route left, or at its end the
  // feet's distance to the goal) has not shrunk by a tenth of d_lim over this many
  // accepted windows ends with status partial, keeping the steps up to its best point
  // (0: off; the step budget and the time limit end it). A window proven infeasible at the
  // longest look is planned again from the window before at most this many times
  // between two gains.
  int max_windows_without_progress = 3;
  // Time budget of each window under route guidance (planner/window_budget.h): this many
  // fair shares of the remaining time, the fair share from the route left over the route
  // covered per window so far (0: the old rule, the larger of an even split over the step
  // budget's windows and half the remaining time, which let early windows spend the
  // time on proofs that later windows needed to reach the goal).
  double window_time_slack = 2.0;
  // A guided window's time share ends its search only once it has a plan; before that it
  // runs on to the plan's own limit (BranchAndBoundOptions::time_limit_needs_incumbent).
  bool anytime_windows = true;
  // ... but for at most this many times its share: a window that finds no plan in that
  // (often an infeasible one the search cannot prove so) must not take the time the
  // retries and later windows need.
  double anytime_window_cap = 4.0;
  // A guided window's search ends once its plan has not improved for this fraction of
  // its time share (BranchAndBoundOptions::stall_time_fraction; 0: off): on fields of
  // many small regions the searches keep the route's plan and spend their whole shares
  // on proofs they cannot finish, time the windows still to come need.
  double window_stall_fraction = 0.25;
  // PlanRequest::warm_start is used when every start foot lies within this of a footstep
  // of the previous plan [m] (a robot's feet land near, not on, the planned spots).
  double warm_start_match_m = 0.05;
  // The first window of a robot standing on its previous plan (PlanRequest::warm_start
  // matched: a robot replanning as it walks) searches at most this long [s] (0: its share
  // of the plan's time, like any window): it needs its answer within its cycle, and asks
  // again from the plan it got, so each replan's search starts from the last one's plan.
  // A search cut short answers its best plan with status feasible and its proven gap;
  // one without a plan by then goes on as the full search.
  double replan_time_s = 0.0;
  FormulationOptions formulation;
  BranchAndBoundOptions branch_and_bound;
  // The seed of each window's search; its stage search options and time limit are set
  // from branch_and_bound and the window's time.
  RelaxAndFixOptions relax_and_fix;
  // Each window's plan solved again with exact sin/cos and its integer assignment fixed
  // (planner/window_polisher.h); when that fails the window keeps the MIQP's plan and
  // the plan's message says so.
  PolishOptions polish;
};

struct PlanProgress {
  int window = 0;          // 1-based
  int steps_planned = 0;   // new footsteps accepted so far
  double distance_to_goal_m = 0.0;
  double elapsed_s = 0.0;
  BranchAndBoundResult window_result;
  PolishReport polish;     // the polisher's account of this window
  WindowRecord record;     // this window's record (also in Plan::window_records)
};

// Nominal stance of the robot at a body pose, feet on the highest region below each
// foot (z = 0 where there is none), in leg order.
std::vector<Eigen::Vector3d> NominalStance(const RobotModel& robot,
                                           const std::vector<ConvexRegion>& regions,
                                           double x_m, double y_m, double yaw_rad);

// Body yaw that best aligns the feet (leg order) with the nominal offsets [rad].
double EstimateStanceYaw(const RobotModel& robot, const std::vector<Eigen::Vector3d>& feet_world_m);

// The MIQP of the first window of a request: the start stance in gait order, the
// window's number of new steps. PlanFootsteps solves exactly this problem first, and
// mfp-plan --write-mps exports it.
FootstepProblem FirstWindowProblem(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                   const PlanRequest& request, const PlannerOptions& options);

// Body yaw of the final configuration of a footstep list [rad]: the yaw its last
// footstep reports, which is the yaw that footstep's reference box was met with (one
// definition for the goal test, the goal cost and the validator; README, plan JSON).
double FinalStanceYaw(const RobotModel& robot, const std::vector<Footstep>& footsteps);

// Plans a whole route. Bad requests come back as statuses (kInvalidRequest,
// kInvalidStart, kInvalidGoal, kNoMap) with a message naming the problem.
// solvers: one per branch-and-bound worker (at least one; see RelaxationSolverOptions::threads).
Plan PlanFootsteps(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   const std::vector<RelaxationSolver*>& solvers,
                   const std::function<void(const PlanProgress&)>& on_progress = {});

// The same with a single worker.
Plan PlanFootsteps(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   RelaxationSolver& solver,
                   const std::function<void(const PlanProgress&)>& on_progress = {});

}  // namespace mfp
