// mfp-plan: plans footsteps for one request from a scenario file or from flags.
// Exit codes: 0 a plan reaching the goal, 2 bad input, 3 no plan reaching the goal (status
// no_route: no route exists, the message names where it breaks; partial: a valid plan
// that stops short, the message says how far it got and why).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "planner/base/check.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/io/plan_json.h"
#include "planner/io/robot_loader.h"
#include "planner/io/scenario_yaml.h"
#include "planner/miqp/mps_writer.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/planning/request_check.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "terrain/map_file.h"
#include "tools/daemon/timestamped_log.h"
#include "tools/plan_svg.h"
#include "tools/text_output.h"

namespace {

constexpr int kExitReached = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitNoPlan = 3;
const char* kProgram = "mfp-plan";

mfp::Pose2D ParsePose(const std::string& text, const std::string& flag) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    try {
      size_t used = 0;
      v.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw mfp::InputError(flag + ": '" + part + "' is not a number (expected X,Y,YAW in m, m, rad)");
    }
  }
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
    throw mfp::InputError(flag + ": expected three finite numbers X,Y,YAW (m, m, rad), got '" + text + "'");
  }
  return {v[0], v[1], v[2]};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mfp-plan: multilegged footstep planning by mixed-integer convex optimisation"};
  std::string scenario_path, robot_path, terrain_path, start_text, goal_text;
  std::string json_path, svg_path, mps_path;
  int max_steps = 0, window = 0;
  double time_limit = 0.0;
  int threads = 0;
  bool validate = false, quiet = false, no_polish = false;
  double polish_time_limit = 0.0;
  std::string relaxation_solver;
  app.add_option("--scenario", scenario_path, "scenario YAML (robot, terrain, start, goal)");
  app.add_option("--robot", robot_path, "robot YAML (or URDF)");
  app.add_option("--terrain", terrain_path, "terrain: .bt/.ot map, or a height map (.npy with its .yaml, or the .yaml)");
  app.add_option("--start", start_text, "start pose X,Y,YAW [m, m, rad]");
  app.add_option("--goal", goal_text, "goal pose X,Y,YAW [m, m, rad]");
  app.add_option("--max-steps", max_steps, "new footsteps in the whole plan (default 12 n)")->check(CLI::Range(1, 100000));
  app.add_option("--window", window, "new footsteps per MIQP (default 2 n; the paper used 4 n)")->check(CLI::Range(1, 1000));
  app.add_option("--time-limit", time_limit, "time limit for the whole plan [s]")->check(CLI::Range(1e-3, 3600.0));
  app.add_option("--json", json_path, "write the plan JSON here ('-' = stdout)");
  app.add_option("--svg", svg_path, "write a picture of the plan here");
  app.add_option("--write-mps", mps_path, "write the first window's MIQP as free MPS (constant left out)");
  app.add_option("--relaxation-solver", relaxation_solver, "ipm (default: mfp's interior point, Ipopt fallback) or ipopt");
  app.add_option("--threads", threads, "branch-and-bound workers solving node relaxations at once (default 1)")
      ->check(CLI::Range(1, 64));
  app.add_flag("--validate", validate, "re-check the plan constraint by constraint; exit 3 on a violation");
  app.add_flag("--quiet", quiet, "no progress lines");
  app.add_flag("--no-polish", no_polish, "keep each window's MIQP plan (sin/cos by chords) instead of solving it again with exact sin/cos");
  app.add_option("--polish-time-limit", polish_time_limit, "time limit of the exact-trigonometry polisher per window [s]")
      ->check(CLI::Range(1e-4, 3600.0));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  auto log = [&](const std::string& line) {
    if (!quiet) mfp::LogLine(kProgram, line);
  };

  // The time limit counts from here: loading the robot and the terrain spend it too.
  const auto run_start = std::chrono::steady_clock::now();
  try {
    mfp::Scenario scenario;
    if (!scenario_path.empty()) {
      if (!robot_path.empty() || !terrain_path.empty()) {
        throw mfp::InputError("--scenario cannot be combined with --robot or --terrain");
      }
      scenario = mfp::LoadScenario(scenario_path);
      if (!start_text.empty()) scenario.start = ParsePose(start_text, "--start");
      if (!goal_text.empty()) scenario.goal = ParsePose(goal_text, "--goal");
    } else {
      if (robot_path.empty() || terrain_path.empty() || start_text.empty() || goal_text.empty()) {
        throw mfp::InputError("give --scenario FILE, or all of --robot, --terrain, --start and --goal");
      }
      scenario.name = terrain_path;
      scenario.robot_path = robot_path;
      scenario.start = ParsePose(start_text, "--start");
      scenario.goal = ParsePose(goal_text, "--goal");
      if (mfp::IsMapFilePath(terrain_path)) {  // an OctoMap or a height map
        scenario.map_path = terrain_path;
      } else {
        throw mfp::InputError("--terrain " + terrain_path + ": expected a .bt or .ot map, or a height map (.npy with its .yaml)");
      }
    }
    const mfp::RobotModel robot = mfp::LoadRobot(scenario.robot_path);
    std::string terrain_note;
    // One deadline for the whole run: region extraction spends the same time limit.
    const double run_limit = time_limit > 0 ? time_limit
                             : scenario.time_limit_s > 0 ? scenario.time_limit_s
                                                         : scenario.options.default_time_limit_s;
    const mfp::Deadline run_deadline = mfp::Deadline::After(
        run_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count());
    const std::vector<mfp::ConvexRegion> regions =
        mfp::ScenarioRegions(scenario, robot, &terrain_note, run_deadline);
    if (!terrain_note.empty()) log("terrain: " + terrain_note);
    log("robot '" + robot.name + "' (" + std::to_string(robot.num_legs()) + " legs), " +
        std::to_string(regions.size()) + " regions");

    mfp::PlannerOptions& options = scenario.options;
    if (!relaxation_solver.empty()) options.solvers.backend = mfp::ParseRelaxationBackend(relaxation_solver);
    mfp::PlanRequest request = mfp::ScenarioRequest(scenario, robot, regions);
    if (max_steps > 0) request.max_steps = max_steps;
    if (window > 0) request.window_steps = window;
    if (time_limit > 0) request.time_limit_s = time_limit;
    request.deadline = run_deadline;

    if (threads > 0) options.solvers.threads = threads;
    if (no_polish) options.polish.enabled = false;
    if (polish_time_limit > 0) options.polish.time_limit_s = polish_time_limit;
    const mfp::RelaxationSolverSet solvers = mfp::MakeRelaxationSolvers(options.solvers);
    // A rejected request (bad start, goal, sizes) exports nothing: PlanFootsteps below
    // answers it with its status and message (exit 2).
    if (!mps_path.empty() && mfp::CheckPlanRequest(robot, regions, request, options).ok()) {
      // The first window's MIQP, exactly as the planner builds it.
      const mfp::FootstepProblem problem = mfp::FirstWindowProblem(robot, regions, request, options);
      const mfp::MiqpFormulation formulation(problem, options.formulation);
      mfp::WriteMpsFile(formulation.miqp(), "mfp", mps_path);
      log("wrote " + mps_path + " (" + std::to_string(formulation.miqp().num_variables()) + " columns, " +
          std::to_string(formulation.miqp().num_rows()) + " rows, " +
          std::to_string(formulation.miqp().num_integer()) + " integer)");
    }

    // Long windows also report each better plan found, with its bound, as they go.
    int windows_done = 0;
    options.branch_and_bound.on_incumbent = [&](const mfp::BranchAndBoundResult& r) {
      if (r.solve_time_s < 1.0) return;
      std::ostringstream line;
      line.precision(7);
      line << "window " << windows_done + 1 << ": incumbent " << r.objective << ", bound " << r.bound;
      line.precision(3);
      line << ", gap " << r.gap << ", " << r.nodes << " nodes, " << r.solve_time_s << " s";
      log(line.str());
    };
    const mfp::Plan plan = mfp::PlanFootsteps(
        robot, regions, request, options, solvers.workers(), [&](const mfp::PlanProgress& p) {
          windows_done = p.window;
          std::ostringstream line;
          line.precision(3);
          line << "window " << p.window << ": " << mfp::ToString(p.window_result.status) << ", "
               << p.steps_planned << " steps so far, " << p.distance_to_goal_m << " m to goal, "
               << p.window_result.nodes << " nodes, gap " << p.window_result.gap << ", "
               << p.elapsed_s << " s";
          log(line.str());
        });

    std::ostringstream summary;
    summary.precision(4);
    const int steps = std::max<int>(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
    summary << "status " << mfp::ToString(plan.status) << ", " << (plan.reaches_goal ? "reaches goal" : "does NOT reach goal")
            << ", " << steps << " steps, objective " << plan.objective << ", gap " << plan.gap << ", "
            << plan.nodes << " nodes, " << plan.relaxations << " relaxations, " << plan.solve_time_s << " s";
    if (!plan.message.empty()) summary << " (" << plan.message << ")";
    log(summary.str());

    if (!json_path.empty()) mfp::WriteTextOutput(json_path, mfp::PlanToJson(plan, robot, regions).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (!svg_path.empty()) {
      mfp::WriteTextOutput(svg_path, mfp::PlanToSvg(plan, robot, regions,
                                         {scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad},
                                         scenario.name));
      log("wrote " + svg_path);
    }
    if (plan.status == mfp::SolveStatus::kInvalidRequest || plan.status == mfp::SolveStatus::kInvalidStart ||
        plan.status == mfp::SolveStatus::kInvalidGoal || plan.status == mfp::SolveStatus::kNoMap) {
      std::cerr << kProgram << ": " << plan.message << "\n";
      return kExitBadInput;
    }
    if (validate && mfp::HasPlan(plan.status)) {
      // Exact trigonometry: no slack for the chords of the MIQP's sin/cos.
      const mfp::ValidationTolerances tol;
      const mfp::ExactExcess excess = mfp::MeasureExactExcess(robot, regions, plan);
      std::ostringstream line;
      line.precision(3);
      line << "largest excess with exact R(yaw): reference box " << std::max(0.0, excess.reference_box_m)
           << " m, reachability box " << std::max(0.0, excess.reachability_box_m) << " m, region "
           << std::max(0.0, excess.region_m) << " m, height " << std::max(0.0, excess.height_m) << " m, yaw change "
           << std::max(0.0, excess.yaw_change_rad) << " rad";
      log(line.str());
      const auto errors = mfp::ValidatePlan(robot, regions, plan,
                                            {scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad,
                                             options.goal_tolerance_m, options.goal_yaw_tolerance_rad},
                                            tol);
      for (const std::string& e : errors) std::cerr << kProgram << ": violation: " << e << "\n";
      if (!errors.empty()) return kExitNoPlan;
      log("validated: every constraint holds");
    }
    if (plan.status == mfp::SolveStatus::kNoRoute || plan.status == mfp::SolveStatus::kPartial) {
      std::cerr << kProgram << ": " << plan.message << "\n";
    }
    return plan.reaches_goal ? kExitReached : kExitNoPlan;
  } catch (const mfp::InputError& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return kExitBadInput;
  }
}
