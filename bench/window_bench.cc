// mfp-window-bench: where a long plan spends its time. Plans one scenario (a map with
// many regions: the scanned corridor, a many-stones field) and prints, per window, the
// regions that entered its MIQP after the reachability filter (of all the map's regions),
// its branch-and-bound nodes, wall time and outcome.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "base/check.h"
#include "io/cli_parse.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"

int main(int argc, char** argv) {
  CLI::App app{"Per-window time and regions of one plan"};
  std::string scenario_path, robot_path;
  double time_limit_s = 0.0;
  app.add_option("scenario", scenario_path, "scenario YAML")->required();
  app.add_option("--robot", robot_path, "robot YAML or URDF instead of the scenario's");
  app.add_option("--time-limit", time_limit_s, "time limit of the plan [s] (default: the scenario's)")
      ->check(CLI::Range(0.01, 3600.0));
  MFP_CLI_PARSE(app, argc, argv);
  try {
    mfp::Scenario scenario = mfp::LoadScenario(scenario_path);
    if (!robot_path.empty()) scenario.robot_path = robot_path;
    const mfp::RobotModel robot = mfp::LoadRobot(scenario.robot_path);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<mfp::ConvexRegion> regions = mfp::ScenarioRegions(scenario, robot);
    const double extract_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    mfp::PlanRequest request = mfp::ScenarioRequest(scenario, robot, regions);
    if (time_limit_s > 0) request.time_limit_s = time_limit_s;
    std::printf("%s, robot '%s' (%d legs): %zu regions extracted in %.2f s\n\n", scenario.name.c_str(),
                robot.name.c_str(), robot.num_legs(), regions.size(), extract_s);
    std::printf("%6s %8s %8s %9s %9s  %s\n", "window", "regions", "nodes", "time_s", "gap", "status");
    const mfp::RelaxationSolverSet solvers =
        mfp::MakeRelaxationSolvers(scenario.options.solvers);
    int max_regions = 0;
    double slowest_s = 0.0;
    const mfp::Plan plan = mfp::PlanFootsteps(
        robot, regions, request, scenario.options, solvers.workers(), [&](const mfp::PlanProgress& p) {
          const mfp::BranchAndBoundResult& r = p.window_result;
          std::printf("%6d %8d %8d %9.3f %9.2g  %s\n", p.window, p.record.regions, r.nodes,
                      r.solve_time_s, r.gap, mfp::ToString(r.status).c_str());
          std::fflush(stdout);
          max_regions = std::max(max_regions, p.record.regions);
          slowest_s = std::max(slowest_s, r.solve_time_s);
        });
    std::printf("\n%s: %s, %s, %zu footsteps, %d windows, %.2f s; at most %d of %zu regions in one window, "
                "slowest window %.2f s\n",
                scenario.name.c_str(), mfp::ToString(plan.status).c_str(),
                plan.reaches_goal ? "reaches the goal" : "short of the goal", plan.footsteps.size(), plan.windows,
                plan.solve_time_s, max_regions, regions.size(), slowest_s);
    return mfp::HasPlan(plan.status) ? 0 : 1;
  } catch (const mfp::InputError& e) {
    std::fprintf(stderr, "mfp-window-bench: %s\n", e.what());
    return 2;
  }
}
