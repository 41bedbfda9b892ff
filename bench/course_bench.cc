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

}  // namespace

int RunCourseBench(const CourseBenchOptions& o) {
  std::vector<std::string> robot_paths = o.robot_paths;
  if (robot_paths.empty()) {
    for (const std::string name : {"littledog", "hexapod", "octopod"}) robot_paths.push_back(o.robots_dir + "/" + name + ".yaml");
  }
  robot_paths.insert(robot_paths.end(), o.extra_robot_paths.begin(), o.extra_robot_paths.end());
  std::vector<RobotModel> robots;
  for (const std::string& path : robot_paths) robots.push_back(LoadRobot(path));
  if (!o.write_dir.empty()) std::filesystem::create_directories(o.write_dir);
  if (!o.plan_dir.empty()) std::filesystem::create_directories(o.plan_dir);
  std::vector<CourseKind> kinds = AllCourseKinds();
  for (CourseKind kind : AllCourseKinds()) {
    if (ToString(kind) == o.only) kinds = {kind};
  }
  std::printf("\nGenerated courses (seed %llu, %d courses, %.0f s per plan, regions: %s)\n",
              static_cast<unsigned long long>(o.seed), o.courses, o.time_limit_s,
              o.top_face_regions ? "true top faces inset by the edge margin" : "extracted from the voxelised boxes");
  std::printf("%-32s %-6s %-14s %6s %8s %6s %-9s %10s %5s %6s %6s %8s %8s %s\n", "course", "route", "status", "steps",
              "time_s", "goal", "verdict", "exact_exc", "wins", "inexact", "replan", "polish_s", "max_pol", "cause");
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
  for (int i = o.first; i < o.courses; ++i) {
    const int r = i % static_cast<int>(robots.size());
    const CourseKind kind = kinds[(i / robots.size()) % kinds.size()];
    Course course;
    try {
      course = GenerateCourse(robots[r], robot_paths[r], kind, o.seed + i);
    } catch (const std::runtime_error& e) {
      std::printf("%-32s generator gave up (not counted): %s\n", (robots[r].name + "_" + ToString(kind)).c_str(), e.what());
      ++generator_gave_up;
      continue;
    }
    if (!o.only.empty() && course.name.find(o.only) == std::string::npos) continue;
    if (!o.write_dir.empty()) {
      std::ofstream(o.write_dir + "/" + course.name + ".yaml") << CourseToScenarioYaml(course, o.time_limit_s);
    }
    Scenario scenario = CourseScenario(course, o.time_limit_s);
    if (o.adjust) o.adjust(&scenario);
    const auto t0 = std::chrono::steady_clock::now();
    const RobotModel& robot = robots[r];
    Plan plan;
    std::string cause;
    std::vector<ConvexRegion> regions;
    int windows = 0, inexact = 0, replanned = 0;
    double polish_s = 0.0, max_polish_ratio = 0.0;
    try {
      PlanRequest request;
      if (o.top_face_regions) {
        regions = TopFaceRegions(course.terrain, course.edge_margin_m, robot.max_slope_rad);
        request = ScenarioRequest(scenario, robot, regions);
      } else {
        // On the voxel map the body keeps clear of the map's obstacles (the checker still
        // judges it against the true boxes).
        ScenarioTerrain terrain = LoadScenarioTerrain(scenario, robot);
        regions = terrain.regions;
        request = ScenarioRequest(scenario, robot, regions);
        if (terrain.map_body_obstacles) request.body_obstacles = std::move(*terrain.map_body_obstacles);
      }
      if (!o.body_check) request.body_obstacles.clear();
      const RelaxationSolverSet solvers = MakeRelaxationSolvers(scenario.options.solvers.backend, 1);
      plan = PlanFootsteps(robot, regions, request, scenario.options, solvers.workers(), [&](const PlanProgress& p) {
        ++windows;
        if (!p.polish.exact) ++inexact;
        if (p.record.replanned) ++replanned;
        polish_s += p.polish.time_s;
        solve_sum += p.window_result.solve_time_s;
        max_polish_ratio = std::max(max_polish_ratio, p.polish.time_s / std::max(p.window_result.solve_time_s, 1e-9));
        if (o.verbose) {
          std::printf("    window %d: %d steps, %.3f m to the goal, %.2f s, %s after %lld nodes\n", p.window,
                      p.steps_planned, p.distance_to_goal_m, p.elapsed_s, ToString(p.window_result.status).c_str(),
                      static_cast<long long>(p.window_result.nodes));
        }
      });
    } catch (const std::exception& e) {
      plan.status = SolveStatus::kInternalError;
      plan.message = e.what();
    }
    const double time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.plan_dir.empty()) std::ofstream(o.plan_dir + "/" + course.name + ".json") << PlanToJson(plan, robot, regions).dump(1) << "\n";
    const int steps = std::max<int>(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
    std::string verdict;
    if (course.route_exists) {
      ++with_route;
      times.push_back(time_s);
      if (NoRouteAnswer(plan)) {
        cause = "false_no_route";
      } else if (!HasPlan(plan.status) && plan.footsteps.size() <= static_cast<size_t>(robot.num_legs())) {
        cause = "no_plan:" + ToString(plan.status);
      } else {
        const CourseVerdict v =
            CheckPlanOnCourse(course.terrain, robot, plan.footsteps, course.goal, course.edge_margin_m);
        if (!v.valid) {
          cause = v.cause;
          plan.message = v.violations.front() + "; " + plan.message;
        } else if (!v.reaches_goal) {
          cause = "short_of_goal";
        }
      }
      verdict = cause.empty() ? "ok" : "FAIL";
      if (cause.empty()) {
        ++with_route_ok;
        steps_ok.push_back(steps);
      }
    } else {
      ++without_route;
      const bool ok = NoRouteAnswer(plan) && time_s <= 2.0;
      if (ok) {
        ++no_route_fast;
      } else {
        cause = NoRouteAnswer(plan) ? "no_route_slow" : "missed_no_route";
        if (plan.reaches_goal) cause = "goal_on_cut_course";
      }
      verdict = ok ? "ok" : "FAIL";
    }
    if (!cause.empty()) ++causes[cause];
    double excess = -kInfinity;
    if (steps > 0) {
      const ExactExcess e = MeasureExactExcess(robot, regions, plan);
      excess = std::max(e.reference_box_m, e.reachability_box_m);
      worst_excess = std::max(worst_excess, excess);
    }
    if (plan.reaches_goal) {
      const double miss = std::remainder(FinalStanceYaw(robot, plan.footsteps) - course.goal.yaw_rad, 2.0 * M_PI);
      if (std::abs(miss) > GoalSpec{}.yaw_tolerance_rad) ++false_yaw_claims;
    }
    windows_all += windows;
    inexact_windows += inexact;
    replanned_windows += replanned;
    polish_sum += polish_s;
    relaxations_all += plan.relaxations;
    fallbacks_all += plan.relaxation_fallbacks;
    plans_with_fallbacks += plan.relaxation_fallbacks > 0 ? 1 : 0;
    std::printf("%-32s %-6s %-14s %6d %8.2f %6s %-9s %10.2e %5d %6d %6d %8.4f %8.3f %s %s\n", course.name.c_str(),
                course.route_exists ? "yes" : "cut", ToString(plan.status).c_str(), steps, time_s,
                plan.reaches_goal ? "yes" : "no", verdict.c_str(), steps > 0 ? excess : 0.0, windows, inexact, replanned, polish_s,
                max_polish_ratio, cause.c_str(), cause.empty() ? "" : ("(" + plan.message + ")").c_str());
    if (o.print_windows) {
      for (size_t w = 0; w < plan.window_records.size(); ++w) {
        const WindowRecord& r = plan.window_records[w];
        std::printf("    window %3zu: %3d steps %4d regions %5d binaries  %-11s %5d nodes %5d QPs  kept %3d  "
                    "limit %5.2f s  build %5.3f  heuristic %5.2f  search %5.2f  polish %5.3f s%s\n",
                    w + 1, r.new_steps, r.regions, r.integer_variables, ToString(r.status).c_str(), r.nodes,
                    r.relaxations, r.kept_steps, r.time_limit_s, r.build_s, r.heuristic_s, r.search_s, r.polish_s,
                    r.kept_steps > 0 && !r.polished ? " (MIQP's steps kept)" : "");
      }
    }
    std::fflush(stdout);
  }
  std::printf("\nSummary\n");
  std::printf("  route exists:   %d/%d planned validly to the goal (%.1f %%)\n", with_route_ok, with_route,
              with_route ? 100.0 * with_route_ok / with_route : 0.0);
  std::printf("  no route:       %d/%d answered 'no route' within 2 s\n", no_route_fast, without_route);
  std::printf("  time per plan (route exists): median %.2f s, 90th percentile %.2f s\n", Quantile(times, 0.5),
              Quantile(times, 0.9));
  std::printf("  steps (valid plans): median %.0f, 90th percentile %.0f\n", Quantile(steps_ok, 0.5),
              Quantile(steps_ok, 0.9));
  std::printf("  exact trigonometry: largest reference/reachability excess %.2e m; %d of %d windows not exact; "
              "%d re-planned within the chords' error; %d goal claims whose final yaw misses the goal's\n",
              worst_excess, inexact_windows, windows_all, replanned_windows, false_yaw_claims);
  std::printf("  polisher: %.3f s over all windows against %.3f s of search (%.1f %%)\n", polish_sum, solve_sum,
              100.0 * polish_sum / std::max(solve_sum, 1e-9));
  std::printf("  relaxation fallbacks: %ld of %ld QPs solved by the fallback solver, in %d plans\n", fallbacks_all,
              relaxations_all, plans_with_fallbacks);
  if (generator_gave_up > 0) std::printf("  generator gave up on %d courses (not counted)\n", generator_gave_up);
  std::printf("  failures by cause:");
  if (causes.empty()) std::printf(" none");
  for (const auto& [c, k] : causes) std::printf(" %s %d;", c.c_str(), k);
  std::printf("\n");
  return with_route - with_route_ok + (without_route - no_route_fast);
}

}  // namespace mfp
