#include "bench/course_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "bench/course_checker.h"
#include "bench/course_generator.h"
#include "io/plan_json.h"
#include "io/robot_loader.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {

namespace {

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5));
  return v[i];
}

bool NoRouteAnswer(const Plan& plan) {
  return plan.status == SolveStatus::kNoRoute;
}

// One course planned: the plan, the regions it was planned on, its wall time and what its
// windows did.
struct CourseRun {
  Plan plan;
  std::vector<ConvexRegion> regions;
  double time_s = 0.0;
  int windows = 0, inexact = 0, replanned = 0;
  double polish_s = 0.0, max_polish_ratio = 0.0;
  double solve_s = 0.0;  // the windows' search time
};

// How one course's plan was judged: its verdict ("ok" or "FAIL"), the failure's cause ("" when
// none), its new steps and its largest excess under exact trigonometry (-infinity without steps).
struct CourseJudgement {
  std::string verdict, cause;
  int steps = 0;
  double excess = -kInfinity;
};

// The whole run's counts, summed over the courses.
struct CourseTally {
  int generator_gave_up = 0;
  int with_route = 0, with_route_ok = 0, without_route = 0, no_route_fast = 0;
  std::vector<double> times, steps_ok;
  std::map<std::string, int> causes;
  // Exact trigonometry (issue 18): the largest reference/reachability excess of any plan
  // under exact R(yaw), windows whose footsteps are not exact, goal claims whose final
  // body yaw misses the goal's.
  double worst_excess = -kInfinity;
  int inexact_windows = 0, replanned_windows = 0, windows_all = 0, false_yaw_claims = 0;
  double polish_sum = 0.0, solve_sum = 0.0;
  long relaxations_all = 0, fallbacks_all = 0;  // the searches' QPs, and those the solver's fallback solved
  int plans_with_fallbacks = 0;
};

void PrintTableHeader(const CourseBenchOptions& o) {
  std::printf("\nGenerated courses (seed %llu, %d courses, %.0f s per plan, regions: %s)\n",
              static_cast<unsigned long long>(o.seed), o.courses, o.time_limit_s,
              o.top_face_regions ? "true top faces inset by the edge margin" : "extracted from the voxelised boxes");
  std::printf("%-32s %-6s %-14s %6s %8s %6s %-9s %10s %5s %6s %6s %8s %8s %s\n", "course", "route", "status", "steps",
              "time_s", "goal", "verdict", "exact_exc", "wins", "inexact", "replan", "polish_s", "max_pol", "cause");
}

// The planner's request for the course: on its true top faces, or on the regions and body
// obstacles of its voxel map (o.top_face_regions); fills run->regions.
PlanRequest CourseRequest(const CourseBenchOptions& o, const Course& course, const Scenario& scenario,
                          const RobotModel& robot, CourseRun* run) {
  PlanRequest request;
  if (o.top_face_regions) {
    run->regions = TopFaceRegions(course.terrain, course.edge_margin_m, robot.max_slope_rad);
    request = ScenarioRequest(scenario, robot, run->regions);
  } else {
    // On the voxel map the body keeps clear of the map's obstacles (the checker still
    // judges it against the true boxes).
    ScenarioTerrain terrain = LoadScenarioTerrain(scenario, robot);
    run->regions = terrain.regions;
    request = ScenarioRequest(scenario, robot, run->regions);
    if (terrain.map_body_obstacles) request.body_obstacles = std::move(*terrain.map_body_obstacles);
  }
  if (!o.body_check) request.body_obstacles.clear();
  return request;
}

// Plans the course end to end (an exception becomes an internal-error plan), timing it and
// counting what its windows did.
CourseRun PlanOneCourse(const CourseBenchOptions& o, const Course& course, const RobotModel& robot) {
  Scenario scenario = CourseScenario(course, o.time_limit_s);
  if (o.adjust) o.adjust(&scenario);
  const auto t0 = std::chrono::steady_clock::now();
  CourseRun run;
  try {
    const PlanRequest request = CourseRequest(o, course, scenario, robot, &run);
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(scenario.options.solvers.backend, 1);
    run.plan = PlanFootsteps(robot, run.regions, request, scenario.options, solvers.workers(), [&](const PlanProgress& p) {
      ++run.windows;
      if (!p.polish.exact) ++run.inexact;
      if (p.record.replanned) ++run.replanned;
      run.polish_s += p.polish.time_s;
      run.solve_s += p.window_result.solve_time_s;
      run.max_polish_ratio = std::max(run.max_polish_ratio, p.polish.time_s / std::max(p.window_result.solve_time_s, 1e-9));
      if (o.verbose) {
        std::printf("    window %d: %d steps, %.3f m to the goal, %.2f s, %s after %lld nodes\n", p.window,
                    p.steps_planned, p.distance_to_goal_m, p.elapsed_s, ToString(p.window_result.status).c_str(),
                    static_cast<long long>(p.window_result.nodes));
      }
    });
  } catch (const std::exception& e) {
    run.plan.status = SolveStatus::kInternalError;
    run.plan.message = e.what();
  }
  run.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

// Why a plan on a course with a route fails ("" when it plans validly to the goal); prefixes
// the checker's first violation to the plan's message.
std::string RouteCourseCause(const Course& course, const RobotModel& robot, Plan* plan) {
  if (NoRouteAnswer(*plan)) return "false_no_route";
  if (!HasPlan(plan->status) && plan->footsteps.size() <= static_cast<size_t>(robot.num_legs())) {
    return "no_plan:" + ToString(plan->status);
  }
  const CourseVerdict v = CheckPlanOnCourse(course.terrain, robot, plan->footsteps, course.goal, course.edge_margin_m);
  if (!v.valid) {
    plan->message = v.violations.front() + "; " + plan->message;
    return v.cause;
  }
  return v.reaches_goal ? "" : "short_of_goal";
}

// Judges the plan (a course with a route: valid to the goal; a cut course: 'no route'
// within 2 s) and adds it to the tally.
CourseJudgement JudgeCourse(const Course& course, const RobotModel& robot, CourseRun* run, CourseTally* tally) {
  Plan& plan = run->plan;
  CourseJudgement j;
  j.steps = std::max<int>(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
  if (course.route_exists) {
    ++tally->with_route;
    tally->times.push_back(run->time_s);
    j.cause = RouteCourseCause(course, robot, &plan);
    j.verdict = j.cause.empty() ? "ok" : "FAIL";
    if (j.cause.empty()) {
      ++tally->with_route_ok;
      tally->steps_ok.push_back(j.steps);
    }
  } else {
    ++tally->without_route;
    const bool ok = NoRouteAnswer(plan) && run->time_s <= 2.0;
    if (ok) {
      ++tally->no_route_fast;
    } else {
      j.cause = NoRouteAnswer(plan) ? "no_route_slow" : "missed_no_route";
      if (plan.reaches_goal) j.cause = "goal_on_cut_course";
    }
    j.verdict = ok ? "ok" : "FAIL";
  }
  if (!j.cause.empty()) ++tally->causes[j.cause];
  return j;
}

// Adds the plan's exactness (excess under exact trigonometry, the final yaw against the
// goal's) and its windows' counts to the tally; sets j->excess.
void TallyExactness(const Course& course, const RobotModel& robot, const CourseRun& run, CourseJudgement* j,
                    CourseTally* tally) {
  const Plan& plan = run.plan;
  if (j->steps > 0) {
    const ExactExcess e = MeasureExactExcess(robot, run.regions, plan);
    j->excess = std::max(e.reference_box_m, e.reachability_box_m);
    tally->worst_excess = std::max(tally->worst_excess, j->excess);
  }
  if (plan.reaches_goal) {
    const double miss = std::remainder(FinalStanceYaw(robot, plan.footsteps) - course.goal.yaw_rad, 2.0 * M_PI);
    if (std::abs(miss) > GoalSpec{}.yaw_tolerance_rad) ++tally->false_yaw_claims;
  }
  tally->windows_all += run.windows;
  tally->inexact_windows += run.inexact;
  tally->replanned_windows += run.replanned;
  tally->polish_sum += run.polish_s;
  tally->solve_sum += run.solve_s;
  tally->relaxations_all += plan.relaxations;
  tally->fallbacks_all += plan.relaxation_fallbacks;
  tally->plans_with_fallbacks += plan.relaxation_fallbacks > 0 ? 1 : 0;
}

void PrintCourseRow(const Course& course, const CourseRun& run, const CourseJudgement& j) {
  const Plan& plan = run.plan;
  std::printf("%-32s %-6s %-14s %6d %8.2f %6s %-9s %10.2e %5d %6d %6d %8.4f %8.3f %s %s\n", course.name.c_str(),
              course.route_exists ? "yes" : "cut", ToString(plan.status).c_str(), j.steps, run.time_s,
              plan.reaches_goal ? "yes" : "no", j.verdict.c_str(), j.steps > 0 ? j.excess : 0.0, run.windows,
              run.inexact, run.replanned, run.polish_s, run.max_polish_ratio, j.cause.c_str(),
              j.cause.empty() ? "" : ("(" + plan.message + ")").c_str());
}

void PrintWindowRecords(const Plan& plan) {
  for (size_t w = 0; w < plan.window_records.size(); ++w) {
    const WindowRecord& r = plan.window_records[w];
    std::printf("    window %3zu: %3d steps %4d regions %5d binaries  %-11s %5d nodes %5d QPs  kept %3d  "
                "limit %5.2f s  build %5.3f  heuristic %5.2f  search %5.2f  polish %5.3f s%s\n",
                w + 1, r.new_steps, r.regions, r.integer_variables, ToString(r.status).c_str(), r.nodes,
                r.relaxations, r.kept_steps, r.time_limit_s, r.build_s, r.heuristic_s, r.search_s, r.polish_s,
                r.kept_steps > 0 && !r.polished ? " (MIQP's steps kept)" : "");
  }
}

void PrintSummary(const CourseTally& t) {
  std::printf("\nSummary\n");
  std::printf("  route exists:   %d/%d planned validly to the goal (%.1f %%)\n", t.with_route_ok, t.with_route,
              t.with_route ? 100.0 * t.with_route_ok / t.with_route : 0.0);
  std::printf("  no route:       %d/%d answered 'no route' within 2 s\n", t.no_route_fast, t.without_route);
  std::printf("  time per plan (route exists): median %.2f s, 90th percentile %.2f s\n", Quantile(t.times, 0.5),
              Quantile(t.times, 0.9));
  std::printf("  steps (valid plans): median %.0f, 90th percentile %.0f\n", Quantile(t.steps_ok, 0.5),
              Quantile(t.steps_ok, 0.9));
  std::printf("  exact trigonometry: largest reference/reachability excess %.2e m; %d of %d windows not exact; "
              "%d re-planned within the chords' error; %d goal claims whose final yaw misses the goal's\n",
              t.worst_excess, t.inexact_windows, t.windows_all, t.replanned_windows, t.false_yaw_claims);
  std::printf("  polisher: %.3f s over all windows against %.3f s of search (%.1f %%)\n", t.polish_sum, t.solve_sum,
              100.0 * t.polish_sum / std::max(t.solve_sum, 1e-9));
  std::printf("  relaxation fallbacks: %ld of %ld QPs solved by the fallback solver, in %d plans\n", t.fallbacks_all,
              t.relaxations_all, t.plans_with_fallbacks);
  if (t.generator_gave_up > 0) std::printf("  generator gave up on %d courses (not counted)\n", t.generator_gave_up);
  std::printf("  failures by cause:");
  if (t.causes.empty()) std::printf(" none");
  for (const auto& [c, k] : t.causes) std::printf(" %s %d;", c.c_str(), k);
  std::printf("\n");
}

}  // namespace

CourseRotation MakeCourseRotation(const CourseBenchOptions& o) {
  CourseRotation rotation;
  rotation.robot_paths = o.robot_paths;
  if (rotation.robot_paths.empty()) {
    for (const std::string name : {"littledog", "hexapod", "octopod"}) {
      rotation.robot_paths.push_back(o.robots_dir + "/" + name + ".yaml");
    }
  }
  rotation.robot_paths.insert(rotation.robot_paths.end(), o.extra_robot_paths.begin(), o.extra_robot_paths.end());
  for (const std::string& path : rotation.robot_paths) rotation.robots.push_back(LoadRobot(path));
  rotation.kinds = AllCourseKinds();
  for (CourseKind kind : AllCourseKinds()) {
    if (ToString(kind) == o.only) rotation.kinds = {kind};
  }
  return rotation;
}

int RunCourseBench(const CourseBenchOptions& o) {
  const CourseRotation rotation = MakeCourseRotation(o);
  if (!o.write_dir.empty()) std::filesystem::create_directories(o.write_dir);
  if (!o.plan_dir.empty()) std::filesystem::create_directories(o.plan_dir);
  PrintTableHeader(o);
  CourseTally tally;
  for (int i = o.first; i < o.courses; ++i) {
    const RobotModel& robot = rotation.robots[rotation.RobotIndex(i)];
    Course course;
    try {
      course = rotation.Generate(i, o.seed);
    } catch (const std::runtime_error& e) {
      std::printf("%-32s generator gave up (not counted): %s\n", (robot.name + "_" + ToString(rotation.Kind(i))).c_str(),
                  e.what());
      ++tally.generator_gave_up;
      continue;
    }
    if (!o.only.empty() && course.name.find(o.only) == std::string::npos) continue;
    if (!o.write_dir.empty()) {
      std::ofstream(o.write_dir + "/" + course.name + ".yaml") << CourseToScenarioYaml(course, o.time_limit_s);
    }
    CourseRun run = PlanOneCourse(o, course, robot);
    if (!o.plan_dir.empty()) {
      std::ofstream(o.plan_dir + "/" + course.name + ".json") << PlanToJson(run.plan, robot, run.regions).dump(1) << "\n";
    }
    CourseJudgement judgement = JudgeCourse(course, robot, &run, &tally);
    TallyExactness(course, robot, run, &judgement, &tally);
    PrintCourseRow(course, run, judgement);
    if (o.print_windows) PrintWindowRecords(run.plan);
    std::fflush(stdout);
  }
  PrintSummary(tally);
  return tally.with_route - tally.with_route_ok + (tally.without_route - tally.no_route_fast);
}

}  // namespace mfp
