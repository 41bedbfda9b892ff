#include "bench/course_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "bench/course_checker.h"
#include "bench/course_generator.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/io/robot_loader.h"

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
  const std::vector<std::string> robot_names = {"littledog", "hexapod", "octopod"};
  std::vector<RobotModel> robots;
  std::vector<std::string> robot_paths;
  for (const auto& name : robot_names) {
    robot_paths.push_back(o.robots_dir + "/" + name + ".yaml");
    robots.push_back(LoadRobot(robot_paths.back()));
  }
  if (!o.write_dir.empty()) std::filesystem::create_directories(o.write_dir);
  const auto& kinds = AllCourseKinds();
  std::printf("\nGenerated courses (seed %llu, %d courses, %.0f s per plan, regions: %s)\n",
              static_cast<unsigned long long>(o.seed), o.courses, o.time_limit_s,
              o.top_face_regions ? "true top faces inset by the edge margin" : "extracted from the voxelised boxes");
  std::printf("%-32s %-6s %-14s %6s %8s %6s %-9s %s\n", "course", "route", "status", "steps", "time_s", "goal",
              "verdict", "cause");
  int generator_gave_up = 0;
  int with_route = 0, with_route_ok = 0, without_route = 0, no_route_fast = 0;
  std::vector<double> times, steps_ok;
  std::map<std::string, int> causes;
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
    if (!o.write_dir.empty()) {
      std::ofstream(o.write_dir + "/" + course.name + ".yaml") << CourseToScenarioYaml(course, o.time_limit_s);
    }
    Scenario scenario;
    scenario.name = course.name;
    scenario.robot_path = robot_paths[r];
    scenario.terrain = course.terrain;
    scenario.start = course.start;
    scenario.goal = course.goal;
    scenario.time_limit_s = o.time_limit_s;
    if (o.adjust) o.adjust(&scenario);
    const auto t0 = std::chrono::steady_clock::now();
    const RobotModel& robot = robots[r];
    Plan plan;
    std::string cause;
    try {
      const std::vector<ConvexRegion> regions =
          o.top_face_regions ? TopFaceRegions(course.terrain, course.edge_margin_m, robot.max_slope_rad)
                             : ScenarioRegions(scenario, robot);
      const PlanRequest request = ScenarioRequest(scenario, robot, regions);
      const RelaxationSolverSet solvers = MakeRelaxationSolvers(scenario.options.relaxation_solver, 1);
      plan = PlanFootsteps(robot, regions, request, scenario.options, solvers.workers());
    } catch (const std::exception& e) {
      plan.status = SolveStatus::kInternalError;
      plan.message = e.what();
    }
    const double time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
    std::printf("%-32s %-6s %-14s %6d %8.2f %6s %-9s %s %s\n", course.name.c_str(), course.route_exists ? "yes" : "cut",
                ToString(plan.status).c_str(), steps, time_s, plan.reaches_goal ? "yes" : "no", verdict.c_str(),
                cause.c_str(), cause.empty() ? "" : ("(" + plan.message + ")").c_str());
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
  if (generator_gave_up > 0) std::printf("  generator gave up on %d courses (not counted)\n", generator_gave_up);
  std::printf("  failures by cause:");
  if (causes.empty()) std::printf(" none");
  for (const auto& [c, k] : causes) std::printf(" %s %d;", c.c_str(), k);
  std::printf("\n");
  return with_route - with_route_ok + (without_route - no_route_fast);
}

}  // namespace mfp
