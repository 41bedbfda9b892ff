#include "planner/planning/footstep_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "planner/base/check.h"
#include "planner/planning/exact_window.h"
#include "planner/planning/goal.h"
#include "planner/planning/relax_and_fix.h"
#include "planner/planning/request_check.h"
#include "planner/planning/route_guide.h"
#include "planner/planning/route_proposals.h"
#include "planner/planning/warm_start.h"
#include "planner/planning/window_budget.h"
#include "terrain/region_reachability.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

Plan Rejected(SolveStatus status, const std::string& message) {
  Plan plan;
  plan.status = status;
  plan.message = message;
  return plan;
}

// Worst (least certain) of two window statuses that both carry a plan.
SolveStatus Combine(SolveStatus a, SolveStatus b) {
  auto rank = [](SolveStatus s) {
    return s == SolveStatus::kOptimal ? 0 : s == SolveStatus::kFeasible ? 1 : 2;
  };
  return rank(a) >= rank(b) ? a : b;
}


// Largest horizontal move of one foot in one step [m]: on each axis d_lim about the
// previous nominal spot plus how far the previous foot may lie from that spot (l_bnd, or
// the start stance's own offset, whichever is larger), as a Euclidean length.
double StepReachXY(const RobotModel& robot, const PlanRequest& request) {
  const int n = robot.num_legs();
  const Eigen::Vector2d centre = StanceCentreXY(request.start_feet_world_m);
  double offset = robot.l_bnd_m;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d d = request.start_feet_world_m[k].head<2>() -
                              NominalFootXY(robot, k, centre.x(), centre.y(), request.start_yaw_rad);
    offset = std::max(offset, d.cwiseAbs().maxCoeff());
  }
  return std::sqrt(2.0) * (robot.d_lim_m + offset);
}

}  // namespace

std::vector<Eigen::Vector3d> NominalStance(const RobotModel& robot,
                                           const std::vector<ConvexRegion>& regions, double x_m,
                                           double y_m, double yaw_rad) {
  std::vector<Eigen::Vector3d> feet;
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d xy = NominalFootXY(robot, leg, x_m, y_m, yaw_rad);
    const int r = FindRegionBelow(regions, xy.x(), xy.y(), 0.0);
    feet.emplace_back(xy.x(), xy.y(), r >= 0 ? regions[r].HeightAt(xy.x(), xy.y()) : 0.0);
  }
  return feet;
}

double EstimateStanceYaw(const RobotModel& robot, const std::vector<Eigen::Vector3d>& feet) {
  MFP_CHECK(static_cast<int>(feet.size()) == robot.num_legs());
  const Eigen::Vector2d centre = StanceCentreXY(feet);
  const Eigen::Vector2d mean_offset = MeanNominalOffset(robot);
  // 2-D Procrustes: the rotation maximising sum (R o_k) . (f_k - centre).
  double sin_sum = 0.0, cos_sum = 0.0;
  for (int k = 0; k < robot.num_legs(); ++k) {
    const Eigen::Vector2d o = robot.legs[k].nominal_offset_body_m - mean_offset;
    const Eigen::Vector2d d = feet[k].head<2>() - centre;
    cos_sum += o.dot(d);
    sin_sum += o.x() * d.y() - o.y() * d.x();
  }
  return std::atan2(sin_sum, cos_sum);
}

double FinalStanceYaw(const RobotModel& /*robot*/, const std::vector<Footstep>& footsteps) {
  MFP_CHECK(!footsteps.empty());
  return footsteps.back().yaw_rad;
}

FootstepProblem FirstWindowProblem(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                   const PlanRequest& request, const PlannerOptions& options) {
  MFP_CHECK(static_cast<int>(request.start_feet_world_m.size()) == robot.num_legs());
  FootstepProblem problem;
  problem.robot = &robot;
  problem.regions = regions;
  for (int i = 0; i < robot.num_legs(); ++i) {
    problem.start_feet_world_m.push_back(request.start_feet_world_m[robot.gait[i]]);
  }
  problem.start_yaw_rad = request.start_yaw_rad;
  problem.goal_x_m = request.goal_x_m;
  problem.goal_y_m = request.goal_y_m;
  problem.goal_yaw_rad = request.goal_yaw_rad;
  problem.num_new_steps = std::min(MaxSteps(robot, request, options), WindowSteps(robot, request, options));
  return problem;
}

Plan PlanFootsteps(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   const std::vector<RelaxationSolver*>& solvers,
                   const std::function<void(const PlanProgress&)>& on_progress) {
  const auto start_time = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start_time).count(); };
  const int n = robot.num_legs();
  MFP_CHECK(n >= 2 && static_cast<int>(robot.gait.size()) == n);

  if (const RequestCheck check = CheckPlanRequest(robot, regions, request, options); !check.ok()) {
    return Rejected(check.status, check.message);
  }
  int max_steps = MaxSteps(robot, request, options);
  const int window = WindowSteps(robot, request, options);
  const double time_limit = request.time_limit_s > 0 ? request.time_limit_s : options.default_time_limit_s;

  // Only regions the start stance can reach (chains of steps within dz_max) enter the
  // MIQPs, and each window sees only those its steps can reach.
  const double step_xy = StepReachXY(robot, request);
  std::vector<ConvexRegion> usable;
  for (int i : ReachableRegionIndices(regions, request.start_feet_world_m, step_xy, robot.dz_max_m,
                                      options.start_tolerance_m)) {
    usable.push_back(regions[static_cast<size_t>(i)]);
  }

  // ---- route guidance: no route, or a body route that sets the step budget ----
  RouteGuide guide;
  const bool guided = options.route_guidance && request.max_windows == 0;
  if (guided) {
    guide = PlanRoute(robot, regions, request.start_feet_world_m, {request.goal_x_m, request.goal_y_m},
                      request.goal_yaw_rad, options.goal_tolerance_m, options.start_tolerance_m);
    if (!guide.connected) {
      Plan rejected = Rejected(SolveStatus::kNoRoute, guide.broken);
      rejected.solve_time_s = elapsed();
      return rejected;
    }
    if (options.stance_route) {
      FollowStanceRoute(robot, usable, request.start_feet_world_m, request.start_yaw_rad,
                        {request.goal_x_m, request.goal_y_m}, request.goal_yaw_rad, &guide);
    }
    if (request.max_steps == 0 && options.default_max_steps == 0) {
      // Enough configurations to walk the route route_step_budget times over at d_lim
      // per configuration; the time limit bounds the work.
      const int configurations =
          static_cast<int>(std::ceil(options.route_step_budget * guide.length_m / robot.d_lim_m)) + 4;
      max_steps = std::min(100000, std::max(max_steps, configurations * n));
    }
  }

  // ---- receding windows ----
  Plan plan;
  plan.status = SolveStatus::kOptimal;
  std::vector<Eigen::Vector3d> stance(n), history(n);
  std::vector<double> stance_yaw(n, request.start_yaw_rad);
  for (int i = 0; i < n; ++i) {
    const int leg = robot.gait[i];
    stance[i] = request.start_feet_world_m[leg];
    Footstep f;
    f.index = i;
    f.leg = leg;
    f.position_world_m = stance[i];
    f.yaw_rad = request.start_yaw_rad;
    const int r = FindRegionBelow(regions, stance[i].x(), stance[i].y(), options.start_tolerance_m);
    f.region_id = r >= 0 ? regions[r].id : -1;
    plan.footsteps.push_back(f);
  }
  history = stance;
  int phase = 0;
  int planned = 0;
  double yaw = request.start_yaw_rad;
  const GoalSpec goal{request.goal_x_m, request.goal_y_m, request.goal_yaw_rad, options.goal_tolerance_m,
                      options.goal_yaw_tolerance_rad};
  auto goal_reached = [&](const std::vector<Footstep>& steps) {
    return WithinGoal(DistancesToGoal(robot, steps, goal), goal);
  };
  plan.reaches_goal = goal_reached(plan.footsteps);
  std::string polish_note;  // the first window whose polished plan was not used, and why
  const double start_progress = guided ? RouteProgress(guide, StanceCentreXY(stance)) : 0.0;
  int accepted_windows = 0;  // windows whose steps were kept, for the time budget

  // Adaptive horizons: a window that is infeasible, finds no plan in its time, or cannot
  // improve on standing still is planned again from the stance before the previous
  // window with a longer horizon (up to max_horizon), so that the steps that led into a
  // dead end can change. A success resets the horizon.
  struct Snapshot {
    std::vector<Eigen::Vector3d> stance, history;
    std::vector<double> stance_yaw;
    int phase = 0, planned = 0;
    double yaw = 0.0, objective = 0.0, bound = 0.0;
    size_t footsteps = 0;
  };
  std::vector<Snapshot> snapshots;
  int horizon = window;
  const int max_horizon = guided ? std::min(1000, options.max_horizon_windows * window) : window;
  auto snapshot = [&] {
    return Snapshot{stance, history, stance_yaw, phase, planned, yaw, plan.objective, plan.bound, plan.footsteps.size()};
  };
  auto restore = [&](const Snapshot& s) {
    stance = s.stance;
    history = s.history;
    stance_yaw = s.stance_yaw;
    phase = s.phase;
    planned = s.planned;
    yaw = s.yaw;
    plan.objective = s.objective;
    plan.bound = s.bound;
    plan.footsteps.resize(s.footsteps);
    plan.reaches_goal = goal_reached(plan.footsteps);
  };
  // Called on a failed window: true when it is worth planning again with a longer look.
  int last_failure = -1;  // steps planned where a window last failed
  auto retry_longer = [&](const std::string& why) {
    if (horizon >= max_horizon || time_limit - elapsed() <= 0.0 || plan.horizon_retries >= 50) return false;
    const bool new_failure = planned > last_failure;
    last_failure = std::max(last_failure, planned);
    if (new_failure && snapshots.size() >= 2) {
      snapshots.pop_back();  // the failed window's own start
      restore(snapshots.back());
      snapshots.pop_back();  // taken again when the window is planned
    } else if (!snapshots.empty()) {
      restore(snapshots.back());
      snapshots.pop_back();
    }
    horizon = std::min(max_horizon, 2 * horizon);
    ++plan.horizon_retries;
    plan.message = why;
    return true;
  };

  while (!plan.reaches_goal && planned < max_steps &&
         (request.max_windows <= 0 || plan.windows < request.max_windows)) {
    const double remaining_time = std::min(time_limit - elapsed(), request.deadline.RemainingSeconds());
    if (remaining_time <= 0.0) {
      plan.status = SolveStatus::kTimeLimit;
      plan.message = (request.deadline.Stopped() ? "stopped after " : "time limit reached after ") +
                     std::to_string(planned) + " steps";
      break;
    }
    snapshots.push_back(snapshot());
    const int steps = std::min(horizon, max_steps - planned);
    const int windows_left = (max_steps - planned + window - 1) / window;
    FootstepProblem problem = FirstWindowProblem(robot, regions, request, options);
    problem.start_feet_world_m = stance;
    problem.gait_phase = phase;
    problem.start_yaw_rad = yaw;
    problem.num_new_steps = steps;
    problem.regions.clear();
    for (int i : WindowRegionIndices(usable, stance, (steps + n - 1) / n, step_xy, robot.dz_max_m)) {
      problem.regions.push_back(usable[static_cast<size_t>(i)]);
    }
    // Default: about one window's walk. A route over stance poses is followed closely (two
    // steps of d_lim per leg); one through region centres more loosely.
    const double lookahead = options.local_goal_lookahead_m >= 0 ? options.local_goal_lookahead_m
                             : guide.from_stances            ? 2.0 * robot.d_lim_m
                                                             : 2.0 * LegReach(robot);
    if (guided && lookahead > 0.0) {
      // The window's goal term pulls toward a point of the route ahead of the stance.
      const Eigen::Vector2d centre = StanceCentreXY(stance);
      const double progress = RouteProgress(guide, centre);
      const double s = progress + lookahead;
      // Only where the route detours: where what is left of it is barely longer than the
      // straight line to the goal, the goal itself pulls the same way.
      const double straight_m = (Eigen::Vector2d(request.goal_x_m, request.goal_y_m) - centre).norm();
      const bool detour = guide.length_m - progress > options.local_goal_detour_ratio * straight_m;
      if (detour && s < guide.length_m) {
        const Eigen::Vector2d local = RoutePoint(guide, s);
        problem.goal_x_m = local.x();
        problem.goal_y_m = local.y();
      }
    }
    if (plan.windows > 0) {
      problem.history_feet_world_m = history;
      problem.start_step_yaw_rad = stance_yaw;
    }
    WindowRecord record;
    record.new_steps = steps;
    record.regions = static_cast<int>(problem.regions.size());
    const auto build_start = Clock::now();
    const MiqpFormulation formulation(problem, options.formulation);
    record.build_s = std::chrono::duration<double>(Clock::now() - build_start).count();
    record.integer_variables = formulation.miqp().num_integer();
    if (plan.windows == 0) {
      plan.integer_variables = formulation.miqp().num_integer();
      plan.objective_offset = formulation.miqp().constant;
    }
    ++plan.windows;
    if (!formulation.infeasible_reason().empty()) {
      plan.status = plan.windows == 1 ? SolveStatus::kInfeasible : plan.status;
      plan.message = formulation.infeasible_reason();
      break;
    }
    BranchAndBoundOptions bnb = options.branch_and_bound;
    // Each window gets its share of the remaining time, and at least half of it when
    // few windows are left (later windows are usually shorter, near the goal).
    bnb.time_limit_s = std::max(remaining_time / windows_left, 0.5 * remaining_time);
    if (guided && options.window_time_slack > 0.0) {
      // Under guidance: a share from the windows the route still needs.
      WindowBudgetInput budget;
      budget.remaining_s = remaining_time;
      const double progress = RouteProgress(guide, StanceCentreXY(stance));
      budget.route_left_m = guide.length_m - progress;
      budget.route_covered_m = progress - start_progress;
      budget.accepted_windows = accepted_windows;
      budget.prior_advance_m = robot.d_lim_m * std::max(1, window / n);
      budget.slack = options.window_time_slack;
      bnb.time_limit_s = WindowTimeShare(budget);
    }
    bnb.time_limit_needs_incumbent = guided && options.anytime_windows;
    // No window runs past the whole plan's limit, whatever it is given, nor, running on
    // to its first plan, past anytime_window_cap shares.
    bnb.deadline = request.deadline.Within(
        bnb.time_limit_needs_incumbent ? std::min(time_limit - elapsed(), options.anytime_window_cap * bnb.time_limit_s)
                                       : time_limit - elapsed());
    if (options.snap_yaw_segments) {
      bnb.equivalent_point = [&formulation](const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                            Eigen::VectorXd* x) {
        return formulation.SnapYawToOneSegment(lower, upper, x);
      };
    }
    bool seeded = !options.relax_and_fix.enabled ||
                  formulation.num_configurations() - 1 < options.relax_and_fix.min_configurations;
    // The first window of a replanning request starts from the client's previous plan.
    WarmStart warm_start;
    for (const std::vector<Footstep>& previous : plan.windows == 1 ? request.warm_start
                                                                    : std::vector<std::vector<Footstep>>{}) {
      WarmStart w = WarmStartFrom(formulation, previous, options.warm_start_match_m);
      warm_start.stance_matched = warm_start.stance_matched || w.stance_matched;
      for (Eigen::VectorXd& x : w.proposals) warm_start.proposals.push_back(std::move(x));
    }
    bool bounded_replan = warm_start.stance_matched && options.replan_time_s > 0.0;
    // A bounded replan solves the previous plan's assignment first (a few milliseconds,
    // not cut by the budget): it is the answer when the bounded search finds nothing
    // better. The search does not start from it: with an incumbent from its root the
    // search goes best-bound at once and, cut short, never dives to a better plan (the
    // robot kept the first plan it got), so it dives for its own first.
    std::optional<Eigen::VectorXd> warm_plan;
    if (bounded_replan && !warm_start.proposals.empty()) {
      warm_plan = SolveWarmStart(formulation, warm_start.proposals, *solvers.front(), bnb.deadline,
                                 bnb.feasibility_tolerance);
    }
    std::vector<Eigen::VectorXd> warm = bounded_replan ? std::vector<Eigen::VectorXd>{} : warm_start.proposals;
    // Plans that follow the route (route_proposals.h): on fields of many small regions
    // the search's own first plans barely move the body; and a search that stalls ends.
    // Not for a bounded replan: its search must dive for a plan of its own (above).
    if (guided && !bounded_replan) bnb.stall_time_fraction = options.window_stall_fraction;
    if (guided && !bounded_replan && options.route_proposals) {
      for (Eigen::VectorXd& x : RouteProposals(formulation, guide, RouteProgress(guide, StanceCentreXY(stance)),
                                                 options.route_proposal)) {
        warm.push_back(std::move(x));
      }
    }
    const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) {
      std::vector<Eigen::VectorXd> proposals = formulation.RoundAlongPlan(relaxed);
      proposals.insert(proposals.end(), warm.begin(), warm.end());
      warm.clear();  // offered once, at the root
      if (!seeded) {  // the root: one relax-and-fix plan (the workers are idle during rounding)
        seeded = true;
        const auto rf_start = Clock::now();
        RelaxAndFixOptions rf = options.relax_and_fix;
        rf.stage = bnb;
        rf.stage.time_limit_needs_incumbent = false;  // a stage out of time is completed by rounding
        // Stage searches are small (nodes_per_stage): strong branching would cost them more
        // than it saves, and their plans came out worse (docs/measurements.md).
        if (rf.stage.branching == BranchingRule::kReliability) rf.stage.branching = BranchingRule::kGroupOrder;
        rf.time_limit_s = rf.time_share * bnb.time_limit_s;
        const RelaxAndFixResult r = rf.two_paths ? RelaxAndFixTwoPaths(formulation, solvers, rf)
                                                 : RelaxAndFix(formulation, solvers, rf);
        if (r.x) proposals.push_back(*r.x);
        record.heuristic_s = std::chrono::duration<double>(Clock::now() - rf_start).count();
      }
      return proposals;
    };
    const double window_time_limit_s = bnb.time_limit_s;
    if (bounded_replan) bnb.time_limit_s = std::min(bnb.time_limit_s, options.replan_time_s);
    const auto search_start = Clock::now();
    BranchAndBoundResult result = SolveBranchAndBound(formulation.miqp(), solvers, bnb, rounding);
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
      result = SolveBranchAndBound(formulation.miqp(), solvers, bnb, rounding);
      result.nodes += first.nodes;
      result.relaxations += first.relaxations;
      bounded_replan = false;
    }
    // Cut short by the replanning budget, not by the request's time: a plan, unproven.
    if (bounded_replan && result.status == SolveStatus::kTimeLimit && request.deadline.RemainingSeconds() > 0.0 &&
        time_limit - elapsed() > 0.0) {
      result.status = SolveStatus::kFeasible;
    }
    record.search_s = std::chrono::duration<double>(Clock::now() - search_start).count();
    record.time_limit_s = bnb.time_limit_s;
    record.status = result.status;
    record.nodes = result.nodes;
    record.relaxations = result.relaxations;
    plan.window_records.push_back(record);
    plan.nodes += result.nodes;
    plan.relaxations += result.relaxations;
    if (!HasPlan(result.status) &&
        retry_longer("window " + std::to_string(plan.windows) + ": " + ToString(result.status))) {
      continue;
    }
    if (!HasPlan(result.status)) {
      if (plan.windows == 1) {
        plan.status = result.status;
      } else {
        plan.status = guided ? plan.status
                             : result.status == SolveStatus::kInfeasible ? plan.status : result.status;
        // Unguided, a later window cut by its time share before its first plan: the plan
        // so far stands, ended by the time limit.
        if (!guided && result.status == SolveStatus::kNoSolution) plan.status = SolveStatus::kTimeLimit;
      }
      plan.message = "window " + std::to_string(plan.windows) + ": " + ToString(result.status) +
                     " after " + std::to_string(result.nodes) + " nodes";
      break;
    }
    // The polisher's time comes out of the plan's: at most what is left of it.
    PolishOptions polish = options.polish;
    polish.time_limit_s = std::min(polish.time_limit_s, std::max(1e-3, time_limit - elapsed()));
    // Under guidance no more than the window's own share (at least 50 ms): the polisher
    // took 0.2-0.4 s of 0.3 s shares on octopod stones; a window it cannot polish in
    // time is planned again within the chords' error (below).
    if (guided && options.window_time_slack > 0.0) {
      polish.time_limit_s = std::min(polish.time_limit_s, std::max(0.05, bnb.time_limit_s));
    }
    const auto polish_start = Clock::now();
    PolishedWindow polished = PolishWindow(formulation, result.x, polish);
    plan.window_records.back().polish_s = std::chrono::duration<double>(Clock::now() - polish_start).count();
    // A window the polisher cannot make exact is planned again within the chords' error
    // (exact_window.h); when that finds no plan the plan ends before this window.
    ExactReplan replan;
    if (!polished.report.message.empty() && !polish.replan_when_inexact && polish_note.empty()) {
      polish_note = "window " + std::to_string(plan.windows) + ": " + polished.report.message;
    }
    if (polish.enabled && polish.replan_when_inexact && !polished.report.exact) {
      bnb.deadline = request.deadline.Within(time_limit - elapsed());
      const double polish_s = polished.report.time_s;
      replan = ReplanWithinChordError(formulation, solvers, bnb, polish);
      if (polish_note.empty()) polish_note = "window " + std::to_string(plan.windows) + ": " + replan.note;
      if (!replan.planned) {
        // A longer look from the window before may find steps that can be made exact
        // (small footholds leave the shrunk boxes no room where the chords' plan had some).
        if (retry_longer("window " + std::to_string(plan.windows) + ": no exact plan (" + replan.note + ")")) continue;
        // Infeasible within the shrunk boxes proves nothing about the true ones (an
        // inexact plan exists): no exact plan found, never a claim of infeasibility.
        if (plan.windows == 1) plan.status = SolveStatus::kNoSolution;
        plan.message = "window " + std::to_string(plan.windows) + ": the polisher could not make it exact (" +
                       polished.report.message + "), " + replan.note;
        break;
      }
      plan.nodes += replan.result.nodes;
      plan.relaxations += replan.result.relaxations;
      result = replan.result;
      polished = std::move(replan.polished);
      polished.report.time_s += polish_s;  // both polishes
    }
    plan.window_records.back().polished = polished.report.accepted;
    plan.window_records.back().replanned = replan.planned;
    const MiqpFormulation& used = replan.planned ? *replan.formulation : formulation;
    plan.status = Combine(plan.status, result.status);
    plan.objective += result.objective;
    plan.bound += result.bound;
    // Keep the untrimmed steps; trimmed ones (a suffix) leave the feet where they are.
    const std::vector<Footstep>& window_steps = polished.footsteps;
    int kept = 0;
    for (int i = n; i < used.num_steps(); ++i) {
      if (result.x(used.vars().trim[i]) < 0.5) kept = i - n + 1;
    }
    for (int i = n; i < n + kept; ++i) {
      Footstep f = window_steps[i];
      f.index = static_cast<int>(plan.footsteps.size());
      plan.footsteps.push_back(f);
    }
    planned += kept;
    if (kept > 0) ++accepted_windows;
    plan.window_records.back().kept_steps = kept;
    phase = (phase + kept) % n;
    const int size = static_cast<int>(plan.footsteps.size());
    for (int i = 0; i < n; ++i) {
      stance[i] = plan.footsteps[size - n + i].position_world_m;
      stance_yaw[i] = plan.footsteps[size - n + i].yaw_rad;
      // Before the plan started the robot stood in its start stance.
      const int before = size - 2 * n + i;
      history[i] = plan.footsteps[before >= 0 ? before : before + n].position_world_m;
    }
    yaw = plan.footsteps.back().yaw_rad;
    plan.reaches_goal = goal_reached(plan.footsteps);
    if (request.on_plan_so_far && kept > 0) {
      Plan so_far = plan;
      so_far.status = plan.reaches_goal ? plan.status : SolveStatus::kPartial;
      so_far.message = "the plan so far: " + std::to_string(planned) + " steps";
      so_far.gap = (plan.objective - plan.bound) / std::max(1.0, std::abs(plan.objective));
      so_far.solve_time_s = elapsed();
      request.on_plan_so_far(so_far);
    }
    if (on_progress) {
      PlanProgress progress;
      progress.window = plan.windows;
      progress.steps_planned = planned;
      progress.distance_to_goal_m = (StanceCentreXY(stance) - Eigen::Vector2d(request.goal_x_m, request.goal_y_m)).norm();
      progress.elapsed_s = elapsed();
      progress.window_result = result;
      progress.polish = polished.report;
      progress.record = plan.window_records.back();
      on_progress(progress);
    }
    if (kept == 0 && !plan.reaches_goal &&
        retry_longer("window " + std::to_string(plan.windows) + " found no step that improves on standing still")) {
      continue;
    }
    // A window whose steps only shuffle the feet (none moved a tenth of d_lim from where
    // it stood one and two windows ago) is stuck as surely as one that keeps none: the
    // next windows would repeat it until the step budget ends.
    if (guided && kept > 0 && !plan.reaches_goal && snapshots.size() >= 2) {
      // Where each leg stood after the first `count` footsteps (the last n cover every leg).
      auto feet_after = [&](size_t count) {
        std::vector<Eigen::Vector3d> feet(n);
        for (size_t k = count - n; k < count; ++k) feet[plan.footsteps[k].leg] = plan.footsteps[k].position_world_m;
        return feet;
      };
      const std::vector<Eigen::Vector3d> now = feet_after(plan.footsteps.size());
      double moved = 0.0;
      for (size_t back = 1; back <= 2; ++back) {
        const std::vector<Eigen::Vector3d> before = feet_after(snapshots[snapshots.size() - back].footsteps);
        for (int leg = 0; leg < n; ++leg) moved = std::max(moved, (now[leg] - before[leg]).norm());
      }
      if (moved < 0.1 * robot.d_lim_m) {
        const std::string why = "window " + std::to_string(plan.windows) + " only shuffled the feet (none moved " +
                                std::to_string(0.1 * robot.d_lim_m) + " m in two windows)";
        if (retry_longer(why)) continue;
        plan.message = "the planner stopped short of the goal: " + why;
        break;
      }
    }
    if (kept > 0) {
      if (planned > last_failure) horizon = window;  // past the dead end: back to short windows
      plan.message.clear();  // a retry's reason, now overcome
    }
    if (kept == 0 && !plan.reaches_goal) {
      plan.message = "the planner stopped short of the goal: window " + std::to_string(plan.windows) +
                     " found no step that improves on standing still";
      break;
    }
  }
  if (!plan.reaches_goal && plan.message.empty() && HasPlan(plan.status)) {
    plan.message = planned < max_steps && request.max_windows > 0
                       ? "goal not reached within " + std::to_string(request.max_windows) + " window(s)"
                       : "goal not reached within " + std::to_string(max_steps) + " steps";
  }
  if (!polish_note.empty()) plan.message += (plan.message.empty() ? "" : "; ") + polish_note;
  if (!plan.reaches_goal && HasPlan(plan.status) && request.max_windows == 0) {
    // Every accepted step satisfies the constraints: the robot can walk this far safely.
    const Eigen::Vector2d centre = StanceCentreXY(stance);
    std::ostringstream msg;
    msg.precision(3);
    msg << "partial plan: " << planned << " steps, stopped "
        << (centre - Eigen::Vector2d(request.goal_x_m, request.goal_y_m)).norm() << " m from the goal: " << plan.message;
    plan.message = msg.str();
    plan.status = SolveStatus::kPartial;
  }
  plan.gap = (plan.objective - plan.bound) / std::max(1.0, std::abs(plan.objective));
  plan.solve_time_s = elapsed();
  return plan;
}

Plan PlanFootsteps(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   RelaxationSolver& solver,
                   const std::function<void(const PlanProgress&)>& on_progress) {
  return PlanFootsteps(robot, regions, request, options, std::vector<RelaxationSolver*>{&solver}, on_progress);
}

}  // namespace mfp
