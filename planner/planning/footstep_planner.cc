#include "planner/planning/footstep_planner.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "base/check.h"
#include "planner/planning/internal/goal.h"
#include "planner/planning/internal/goal_footholds.h"
#include "planner/planning/internal/horizon_policy.h"
#include "planner/planning/internal/horizon_state.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/planning/internal/plan_outcome.h"
#include "planner/planning/internal/plan_progress.h"
#include "planner/planning/internal/window_body_check.h"
#include "planner/planning/internal/window_exactness.h"
#include "planner/planning/internal/window_problem.h"
#include "planner/planning/internal/window_search.h"
#include "planner/planning/request_check.h"

namespace mfp {

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

namespace {

struct GoalChoice {
  std::optional<Plan> rejected;         // invalid_goal: no certified stance within the tolerances
  std::optional<GoalPose> moved;        // plan to this instead of the request's goal
  std::vector<ConvexRegion> footholds;  // goal footholds on seen floor, planned on beside the regions
  std::string note;                     // why the goal moved
};

std::string PoseText(const GoalPose& p) {
  std::ostringstream s;
  s.precision(3);
  s << "(" << p.x_m << ", " << p.y_m << ", yaw " << p.yaw_rad << ")";
  return s.str();
}

// For an invalid_goal message: "; the nearest stance on regions is (x, y, yaw), d m away"
// from the search beyond the goal tolerances (goal_search.report_radius, turns within
// the heading tolerance), or why none is named.
std::string FartherStanceText(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const GoalPose& goal,
                              const PlannerOptions& options, const Deadline& deadline) {
  const double radius_m = options.goal_report_radius_m;
  if (!(radius_m > options.goal_position_tolerance_m)) return "";
  // Turns of the whole heading tolerance either way (a step no smaller than the search's,
  // so a tolerance of 0 asks for no turn rather than a zero step).
  const double yaw_step = std::max(options.goal_heading_tolerance_rad, options.goal_search_yaw_step_rad);
  const std::optional<GoalPose> farther =
      NearestCertifiedGoal(robot, regions, goal, radius_m, options.goal_heading_tolerance_rad, options.goal_report_step_m,
                           yaw_step, 0.0, deadline);
  std::ostringstream text;
  text.precision(3);
  if (farther) {
    text << "; the nearest stance on regions is " << PoseText(*farther) << ", "
         << std::hypot(farther->x_m - goal.x_m, farther->y_m - goal.y_m) << " m away";
  } else if (deadline.Expired()) {
    text << "; the search for the nearest stance on regions farther out was cut short by the time limit";
  } else {
    text << "; no stance on regions within " << radius_m << " m either";
  }
  return text.str();
}

// The goal stance on seen floor within the tolerances (SeenFootholdGoal), when there is one:
// `why` (where the regions leave the goal out) and the legs on footholds make its note.
std::optional<GoalChoice> FootholdChoice(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                         const PlanRequest& request, const PlannerOptions& options,
                                         const std::string& why) {
  if (request.seen_surface == nullptr) return std::nullopt;
  const GoalPose goal{request.goal_x_m, request.goal_y_m, request.goal_yaw_rad};
  std::optional<FootholdGoal> found =
      SeenFootholdGoal(robot, regions, *request.seen_surface, goal, options, request.deadline);
  if (!found) return std::nullopt;
  std::ostringstream note;
  note.precision(3);
  note << why << "; planned to the nearest stance on regions and seen floor " << PoseText(found->pose)
       << ", with footholds on the seen floor for leg";
  for (size_t k = 0; k < found->legs.size(); ++k) {
    note << (k == 0 ? " " : ", ") << found->legs[k] << " near (" << found->spots_m[k].x() << ", "
         << found->spots_m[k].y() << ")";
  }
  GoalChoice choice;
  choice.moved = found->pose;
  choice.footholds = std::move(found->footholds);
  choice.note = note.str();
  return choice;
}

// Under route guidance a goal stance must stand on regions (the route guide's test). One
// with a foot spot on none is moved to the nearest certified stance within the goal
// tolerances; beyond them the request is invalid_goal, naming the foot and the nearest
// certified stance farther out. The request has passed CheckPlanRequest.
GoalChoice ChooseGoal(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const PlanRequest& request,
                      const PlannerOptions& options) {
  GoalChoice choice;
  if (!options.route_guidance || request.max_windows != 0) return choice;
  const GoalPose goal{request.goal_x_m, request.goal_y_m, request.goal_yaw_rad};
  const double tol = options.goal_tolerance_m;
  const int leg = LegOffRegions(robot, regions, goal, tol);
  if (leg < 0) return choice;
  const Eigen::Vector2d spot = NominalFootXY(robot, leg, goal.x_m, goal.y_m, goal.yaw_rad);
  std::ostringstream why;
  why.precision(3);
  why << "the goal " << PoseText(goal) << " puts leg " << leg << " ('" << robot.legs[leg].name << "') at ("
      << spot.x() << ", " << spot.y() << "), on no region";
  // The stance moved to has every spot inside a region, not merely within the goal
  // tolerance of one: its feet must be able to stand on their spots exactly.
  choice.moved = NearestCertifiedGoal(robot, regions, goal, options.goal_position_tolerance_m,
                                      options.goal_heading_tolerance_rad, options.goal_search_step_m,
                                      options.goal_search_yaw_step_rad, 0.0,
                                      request.deadline);
  if (request.deadline.Expired()) {
    choice.moved.reset();
    choice.rejected = Rejected(SolveStatus::kTimeLimit, why.str() + "; " +
                                                            (request.deadline.Stopped() ? "stopped" : "time limit reached") +
                                                            " while looking for a goal stance on regions");
    return choice;
  }
  if (choice.moved) {
    choice.note = why.str() + "; planned to the nearest stance on regions " + PoseText(*choice.moved);
    return choice;
  }
  if (std::optional<GoalChoice> on_seen_floor = FootholdChoice(robot, regions, request, options, why.str())) {
    return *on_seen_floor;
  }
  if (request.deadline.Expired()) {  // the foothold search ran out of time: not a verdict on the goal
    choice.rejected = Rejected(SolveStatus::kTimeLimit, why.str() + "; " +
                                                            (request.deadline.Stopped() ? "stopped" : "time limit reached") +
                                                            " while looking for a goal stance on seen floor");
    return choice;
  }
  why << "; no stance on regions within goal_position_tolerance " << options.goal_position_tolerance_m
      << " m and goal_heading_tolerance " << options.goal_heading_tolerance_rad << " rad";
  choice.rejected = Rejected(SolveStatus::kInvalidGoal, why.str() + FartherStanceText(robot, regions, goal, options,
                                                                                      request.deadline));
  return choice;
}

// The receding-horizon loop (the units are in internal/): each pass plans one window
// from the horizon's stance, makes its plan exact and keeps its steps; the policy backs
// up for a longer look where a window fails or the horizon is stuck, and ends a plan that
// has stopped making progress; the outcome names how the plan ends.
Plan PlanWindows(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   const std::vector<RelaxationSolver*>& solvers,
                   const std::function<void(const PlanProgress&)>& on_progress) {
  PlanContext context(robot, regions, request, options, solvers);
  if (std::optional<Plan> rejected = SetUpPlan(&context)) return *rejected;
  HorizonState state(context);
  state.plan.setup_s = context.ElapsedSeconds();
  HorizonPolicy policy(context);
  // The next window is planned again with its body regions (HorizonPolicy::RetryClearOfBody);
  // not again once such a window had no plan, until a window is accepted (a map's obstacles
  // can leave no body region for the start stance, docs/body_clearance.md).
  bool retry_clear_of_body = false;
  bool clear_of_body_failed = false;
  while (state.WantsAnotherWindow()) {
    const bool clear_of_body = std::exchange(retry_clear_of_body, false);
    const double remaining_s = context.RemainingSeconds();
    if (remaining_s <= 0.0) {
      EndOnTimeLimit(context, &state);
      break;
    }
    state.TakeSnapshot();
    FootstepProblem problem =
        NextWindowProblem(context, state, policy.NextWindowSteps(state), policy.LookaheadScale(), clear_of_body);
    FormulationOptions formulation_options = options.formulation;
    formulation_options.body_regions = formulation_options.body_regions || clear_of_body;
    if (policy.finishing()) FinishGoalWeights(context, &problem);
    WindowRecord record;
    record.new_steps = problem.num_new_steps;
    record.regions = static_cast<int>(problem.regions.size());
    const PlanClock::time_point build_start = PlanClock::now();
    const MiqpFormulation formulation(problem, formulation_options, context.request.deadline.Within(remaining_s));
    record.build_s = SecondsSince(build_start);
    if (formulation.out_of_time()) {
      EndOnTimeLimit(context, &state);
      break;
    }
    record.integer_variables = formulation.miqp().num_integer();
    state.CountWindow(formulation);
    if (!formulation.infeasible_reason().empty()) {
      // Infeasible as built: the steps before may have led into it (from the start, nothing can).
      if (state.snapshots.size() >= 2 &&
          policy.RetryLonger(state.WindowName() + ": " + formulation.infeasible_reason(), &state, true)) {
        continue;
      }
      EndOnInfeasibleWindow(formulation.infeasible_reason(), &state);
      break;
    }
    WindowSearch search = SearchWindow(context, formulation, WindowSearchOptions(context, state, remaining_s, formulation),
                                       state.plan.windows == 1, StanceCentreXY(state.stance), &record);
    state.RecordWindow(record);
    if (!HasPlan(search.result.status)) {
      // Kept clear of the body's obstacles the window has no plan: closer local goals instead.
      clear_of_body_failed = clear_of_body_failed || clear_of_body;
      if (clear_of_body && policy.ReplanCloser(state.WindowName() + ": " + ToString(search.result.status), &state)) {
        continue;
      }
      // Body regions make a stricter problem than the window's own: their infeasibility
      // proves nothing about the steps before it.
      if (policy.RetryLonger(state.WindowName() + ": " + ToString(search.result.status), &state,
                             !clear_of_body && search.result.status == SolveStatus::kInfeasible)) {
        continue;
      }
      EndOnFailedSearch(context, search.result, &state);
      break;
    }
    const ExactWindow exact = MakeWindowExact(context, formulation, std::move(search), state.planned == 0);
    state.plan.window_records.back().polish_s = exact.polish_s;
    if (state.polish_note.empty() && !exact.note.empty()) state.polish_note = state.WindowName() + ": " + exact.note;
    if (exact.NoExactPlan()) {
      // A longer look from the window before may find steps that can be made exact
      // (small footholds leave the shrunk boxes no room where the chords' plan had some).
      if (policy.RetryLonger(state.WindowName() + ": no exact plan (" + exact.replan.note + ")", &state)) continue;
      EndOnInexactWindow(exact, &state);
      break;
    }
    if (const std::optional<std::string> clash = WindowBodyClash(context, exact.polished.footsteps,
                                                                     state.KeptSteps(exact.Used(formulation), exact.result))) {
      // Between the route's clear poses the window's yaw is free: the same window kept
      // clear of the obstacles by its body regions, and when that clashes too (the regions
      // hold the body's box at its configurations, the check its exact plan) closer local goals.
      // (With formulation.body_regions on, the window had them already: a retry would
      // find the same plan.)
      if (!formulation_options.body_regions && !clear_of_body_failed && policy.RetryClearOfBody(state.WindowName() + ": " + *clash, &state)) {
        retry_clear_of_body = true;
        continue;
      }
      if (policy.ReplanCloser(state.WindowName() + ": " + *clash, &state)) continue;
    }
    RecordExactness(exact, &state.plan);
    const int kept = state.Accept(exact.Used(formulation), exact.result, exact.polished.footsteps);
    clear_of_body_failed = false;
    ReportWindow(context, state, kept, exact, on_progress);
    state.NoteProgress(RemainingWay(context, state.plan.footsteps), MinProgressGain(context));
    if (const std::optional<std::string> stuck = policy.Stuck(state, kept)) {
      if (policy.FinishAtGoal(&state)) continue;
      if (policy.RetryLonger(*stuck, &state)) continue;
      EndStuck(*stuck, &state);
      break;
    }
    policy.OnStepsKept(&state, kept);
    if (const std::optional<std::string> stalled = policy.Stalled(state)) {
      if (policy.FinishAtGoal(&state)) continue;
      EndStalled(*stalled, &state);
      break;
    }
  }
  return FinishPlan(context, &state);
}

}  // namespace

Plan PlanFootsteps(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   const std::vector<RelaxationSolver*>& solvers,
                   const std::function<void(const PlanProgress&)>& on_progress) {
  // Checked once here: the goal search below and the windows' set-up take it as checked.
  const bool guided = options.route_guidance && request.max_windows == 0;
  GoalChoice choice;
  const RequestCheck check = CheckPlanRequest(robot, regions, request, options);
  std::optional<GoalChoice> on_seen_floor;
  if (!check.ok() && check.status == SolveStatus::kInvalidGoal && guided) {
    // A goal beyond a leg's reach of every region may still stand on seen floor.
    on_seen_floor = FootholdChoice(robot, regions, request, options, check.message);
  }
  if (on_seen_floor) {
    choice = std::move(*on_seen_floor);
  } else if (!check.ok()) {
    Plan plan = Rejected(check.status, check.status == SolveStatus::kInvalidGoal && guided
                                           ? check.message + FartherStanceText(robot, regions,
                                                                               {request.goal_x_m, request.goal_y_m,
                                                                                request.goal_yaw_rad},
                                                                               options, request.deadline)
                                           : check.message);
    plan.goal_x_m = request.goal_x_m;
    plan.goal_y_m = request.goal_y_m;
    plan.goal_yaw_rad = request.goal_yaw_rad;
    return plan;
  } else {
    choice = ChooseGoal(robot, regions, request, options);
  }
  Plan plan;
  if (choice.rejected) {
    plan = std::move(*choice.rejected);
  } else {
    PlanRequest aimed = request;
    if (choice.moved) {
      aimed.goal_x_m = choice.moved->x_m;
      aimed.goal_y_m = choice.moved->y_m;
      aimed.goal_yaw_rad = choice.moved->yaw_rad;
    }
    std::vector<ConvexRegion> footholds = std::move(choice.footholds);
    if (guided) {
      const int next_id = NextRegionId(footholds, NextRegionId(regions));
      const std::vector<ConvexRegion> at_start = StartFootholds(robot, regions, request, options, next_id);
      footholds.insert(footholds.end(), at_start.begin(), at_start.end());
    }
    if (footholds.empty()) {
      plan = PlanWindows(robot, regions, aimed, options, solvers, on_progress);
    } else {
      std::vector<ConvexRegion> with_footholds = regions;
      with_footholds.insert(with_footholds.end(), footholds.begin(), footholds.end());
      plan = PlanWindows(robot, with_footholds, aimed, options, solvers, on_progress);
      plan.footholds = std::move(footholds);
    }
    if (choice.moved) {
      plan.goal_moved = true;
      plan.message = choice.note + (plan.message.empty() ? "" : "; " + plan.message);
    }
  }
  const GoalPose aimed = choice.moved ? *choice.moved : GoalPose{request.goal_x_m, request.goal_y_m, request.goal_yaw_rad};
  plan.goal_x_m = aimed.x_m;
  plan.goal_y_m = aimed.y_m;
  plan.goal_yaw_rad = aimed.yaw_rad;
  return plan;
}

Plan PlanFootsteps(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                   const PlanRequest& request, const PlannerOptions& options,
                   RelaxationSolver& solver,
                   const std::function<void(const PlanProgress&)>& on_progress) {
  return PlanFootsteps(robot, regions, request, options, std::vector<RelaxationSolver*>{&solver}, on_progress);
}

}  // namespace mfp
