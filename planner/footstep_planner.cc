#include "planner/footstep_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "planner/check.h"
#include "planner/relax_and_fix.h"
#include "planner/route_guide.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

Plan Rejected(SolveStatus status, const std::string& message) {
  Plan plan;
  plan.status = status;
  plan.message = message;
  return plan;
}

// Distance in plan view from (x, y) to a region's polygon (0 inside).
double PlanarDistance(const ConvexRegion& region, const Eigen::Vector2d& q) {
  const auto& v = region.vertices_world_m;
  bool inside = true;
  double best = kInfinity;
  for (size_t k = 0; k < v.size(); ++k) {
    const Eigen::Vector2d a = v[k].head<2>(), b = v[(k + 1) % v.size()].head<2>();
    const Eigen::Vector2d e = b - a;
    if (e.x() * (q - a).y() - e.y() * (q - a).x() < 0) inside = false;
    const double t = std::clamp((q - a).dot(e) / std::max(e.squaredNorm(), 1e-18), 0.0, 1.0);
    best = std::min(best, (a + t * e - q).norm());
  }
  return inside ? 0.0 : best;
}

int ChooseValue(int requested, int fallback) { return requested > 0 ? requested : fallback; }

int MaxSteps(const RobotModel& robot, const PlanRequest& request, const PlannerOptions& options) {
  return ChooseValue(request.max_steps, ChooseValue(options.default_max_steps, 12 * robot.num_legs()));
}

int WindowSteps(const RobotModel& robot, const PlanRequest& request, const PlannerOptions& options) {
  return ChooseValue(request.window_steps, ChooseValue(options.default_window_steps, 2 * robot.num_legs()));
}

// Worst (least certain) of two window statuses that both carry a plan.
SolveStatus Combine(SolveStatus a, SolveStatus b) {
  auto rank = [](SolveStatus s) {
    return s == SolveStatus::kOptimal ? 0 : s == SolveStatus::kFeasible ? 1 : 2;
  };
  return rank(a) >= rank(b) ? a : b;
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
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& f : feet) centre += f.head<2>();
  centre /= static_cast<double>(feet.size());
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

double FinalStanceYaw(const RobotModel& robot, const std::vector<Footstep>& footsteps) {
  const int n = robot.num_legs();
  MFP_CHECK(static_cast<int>(footsteps.size()) >= n);
  std::vector<Eigen::Vector3d> feet(n);
  for (size_t i = footsteps.size() - n; i < footsteps.size(); ++i) {
    feet[footsteps[i].leg] = footsteps[i].position_world_m;
  }
  return EstimateStanceYaw(robot, feet);
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

  // ---- request validation: every rejection names the problem ----
  if (regions.empty()) return Rejected(SolveStatus::kNoMap, "no terrain regions: no map yet or the map has no walkable surface");
  if (static_cast<int>(request.start_feet_world_m.size()) != n) {
    return Rejected(SolveStatus::kInvalidRequest,
                    "start stance has " + std::to_string(request.start_feet_world_m.size()) +
                        " feet; robot '" + robot.name + "' has " + std::to_string(n) + " legs");
  }
  for (int k = 0; k < n; ++k) {
    if (!request.start_feet_world_m[k].allFinite()) {
      return Rejected(SolveStatus::kInvalidRequest, "start foot of leg " + std::to_string(k) + " is not finite");
    }
  }
  if (!std::isfinite(request.start_yaw_rad) || !std::isfinite(request.goal_x_m) ||
      !std::isfinite(request.goal_y_m) || !std::isfinite(request.goal_yaw_rad) ||
      !std::isfinite(request.time_limit_s)) {
    return Rejected(SolveStatus::kInvalidRequest, "start yaw, goal pose and time limit must be finite numbers");
  }
  int max_steps = MaxSteps(robot, request, options);
  const int window = WindowSteps(robot, request, options);
  const double time_limit = request.time_limit_s > 0 ? request.time_limit_s : options.default_time_limit_s;
  if (request.max_steps < 0 || max_steps > 100000 || request.window_steps < 0 || window > 1000 ||
      request.time_limit_s < 0 || request.max_windows < 0) {
    return Rejected(SolveStatus::kInvalidRequest,
                    "max_steps must be in [0, 100000], window in [0, 1000], time limit >= 0 s, max_windows >= 0");
  }
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d& f = request.start_feet_world_m[k];
    bool on_region = false;
    for (const ConvexRegion& r : regions) on_region = on_region || RegionContains(r, f, options.start_tolerance_m);
    if (!on_region) {
      std::ostringstream msg;
      msg << "start foot of leg " << k << " ('" << robot.legs[k].name << "') at (" << f.x() << ", "
          << f.y() << ", " << f.z() << ") m is not on any region (tolerance " << options.start_tolerance_m << " m)";
      return Rejected(SolveStatus::kInvalidStart, msg.str());
    }
  }
  double reach = 0.0;
  for (const LegModel& leg : robot.legs) reach = std::max(reach, leg.nominal_offset_body_m.norm());
  double goal_distance = kInfinity;
  for (const ConvexRegion& r : regions) {
    goal_distance = std::min(goal_distance, PlanarDistance(r, Eigen::Vector2d(request.goal_x_m, request.goal_y_m)));
  }
  if (goal_distance > reach + robot.l_bnd_m) {
    std::ostringstream msg;
    msg << "goal (" << request.goal_x_m << ", " << request.goal_y_m << ") m is " << goal_distance
        << " m from the nearest region; the robot's feet reach " << reach + robot.l_bnd_m << " m from its centre";
    return Rejected(SolveStatus::kInvalidGoal, msg.str());
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
    if (request.max_steps == 0 && options.default_max_steps == 0) {
      // Enough configurations to walk the route three times over at d_lim per
      // configuration; the time limit bounds the work.
      const int configurations = static_cast<int>(std::ceil(3.0 * guide.length_m / robot.d_lim_m)) + 4;
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
  auto goal_reached = [&](const std::vector<Footstep>& steps) {
    const double goal_yaw = request.goal_yaw_rad;
    const int size = static_cast<int>(steps.size());
    for (int i = size - n; i < size; ++i) {
      const Eigen::Vector2d g = NominalFootXY(robot, steps[i].leg, request.goal_x_m, request.goal_y_m, goal_yaw);
      if ((steps[i].position_world_m.head<2>() - g).norm() > options.goal_tolerance_m) return false;
    }
    return std::abs(std::remainder(FinalStanceYaw(robot, steps) - goal_yaw, 2 * M_PI)) <=
           options.goal_yaw_tolerance_rad;
  };
  plan.reaches_goal = goal_reached(plan.footsteps);

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
    const double remaining_time = time_limit - elapsed();
    if (remaining_time <= 0.0) {
      plan.status = SolveStatus::kTimeLimit;
      plan.message = "time limit reached after " + std::to_string(planned) + " steps";
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
    const double lookahead = options.local_goal_lookahead_m < 0 ? 2.0 * reach : options.local_goal_lookahead_m;
    if (guided && lookahead > 0.0) {
      // The window's goal term pulls toward a point of the route ahead of the stance.
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (const Eigen::Vector3d& f : stance) centre += f.head<2>();
      centre /= n;
      const double s = RouteProgress(guide, centre) + lookahead;
      if (s < guide.length_m) {
        const Eigen::Vector2d local = RoutePoint(guide, s);
        problem.goal_x_m = local.x();
        problem.goal_y_m = local.y();
      }
    }
    if (plan.windows > 0) {
      problem.history_feet_world_m = history;
      problem.start_step_yaw_rad = stance_yaw;
    }
    const MiqpFormulation formulation(problem, options.formulation);
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
    if (options.snap_yaw_segments) {
      bnb.equivalent_point = [&formulation](const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                            Eigen::VectorXd* x) {
        return formulation.SnapYawToOneSegment(lower, upper, x);
      };
    }
    bool seeded = !options.relax_and_fix ||
                  formulation.num_blocks() - 1 < options.relax_and_fix_min_configurations;
    const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) {
      std::vector<Eigen::VectorXd> proposals = formulation.RoundAlongPlan(relaxed);
      if (!seeded) {  // the root: one relax-and-fix plan (the workers are idle during rounding)
        seeded = true;
        RelaxAndFixOptions rf;
        rf.stage = bnb;
        // Stage searches are small (nodes_per_stage): strong branching would cost them more
        // than it saves, and their plans came out worse (littledog 24: the first plan
        // within 0.5 % at 30 s instead of 0.28 s).
        if (rf.stage.branching == BranchingRule::kReliability) rf.stage.branching = BranchingRule::kGroupOrder;
        rf.time_limit_s = options.relax_and_fix_time_share * bnb.time_limit_s;
        rf.hull_for_later_steps = options.relax_and_fix_region_hull;
        rf.stage_relaxation_tolerance = options.relax_and_fix_stage_tolerance;
        rf.stage_rounding = options.relax_and_fix_stage_rounding;
        const RelaxAndFixResult r = options.relax_and_fix_two_paths ? RelaxAndFixTwoPaths(formulation, solvers, rf)
                                                                    : RelaxAndFix(formulation, solvers, rf);
        if (r.x) proposals.push_back(*r.x);
      }
      return proposals;
    };
    const BranchAndBoundResult result = SolveBranchAndBound(formulation.miqp(), solvers, bnb, rounding);
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
      }
      plan.message = "window " + std::to_string(plan.windows) + ": " + ToString(result.status) +
                     " after " + std::to_string(result.nodes) + " nodes";
      break;
    }
    plan.status = Combine(plan.status, result.status);
    plan.objective += result.objective;
    plan.bound += result.bound;
    // Keep the untrimmed steps; trimmed ones (a suffix) leave the feet where they are.
    const std::vector<Footstep> window_steps = formulation.ExtractFootsteps(result.x);
    int kept = 0;
    for (int i = n; i < formulation.num_steps(); ++i) {
      if (result.x(formulation.vars().trim[i]) < 0.5) kept = i - n + 1;
    }
    for (int i = n; i < n + kept; ++i) {
      Footstep f = window_steps[i];
      f.index = static_cast<int>(plan.footsteps.size());
      plan.footsteps.push_back(f);
    }
    planned += kept;
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
    if (on_progress) {
      PlanProgress progress;
      progress.window = plan.windows;
      progress.steps_planned = planned;
      const Eigen::Vector2d centre = [&] {
        Eigen::Vector2d c = Eigen::Vector2d::Zero();
        for (const Eigen::Vector3d& f : stance) c += f.head<2>();
        return Eigen::Vector2d(c / n);
      }();
      progress.distance_to_goal_m = (centre - Eigen::Vector2d(request.goal_x_m, request.goal_y_m)).norm();
      progress.elapsed_s = elapsed();
      progress.window_result = result;
      on_progress(progress);
    }
    if (kept == 0 && !plan.reaches_goal &&
        retry_longer("window " + std::to_string(plan.windows) + " found no step that improves on standing still")) {
      continue;
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
  if (!plan.reaches_goal && HasPlan(plan.status) && request.max_windows == 0) {
    // Every accepted step satisfies the constraints: the robot can walk this far safely.
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const Eigen::Vector3d& f : stance) centre += f.head<2>();
    centre /= n;
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
