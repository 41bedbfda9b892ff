// mfp-plan: plans footsteps for one request from a scenario file or from flags.
// Exit codes: 0 a plan reaching the goal, 2 bad input, 3 no plan reaching the goal (status
// no_route: no route exists, the message names where it breaks; partial: a valid plan
// that stops short, the message says how far it got and why).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>

#include "base/check.h"
#include "io/cli_parse.h"
#include "io/cli_values.h"
#include "io/map_file.h"
#include "io/plan_json.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "io/text_output.h"
#include "io/timestamped_log.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/mps_writer.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/planning/request_check.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tools/options_reference.h"
#include "tools/plan_svg.h"

namespace {

constexpr int kExitReached = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitNoPlan = 3;
const char* kProgram = "mfp-plan";
using Log = std::function<void(const std::string&)>;

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

// The command line.
struct Flags {
  std::string scenario_path, robot_path, terrain_path, start_text, goal_text;
  std::string json_path, svg_path, mps_path, relaxation_solver;
  int max_steps = 0, window = 0, threads = 0;
  double time_limit = 0.0, polish_time_limit = 0.0;
  bool validate = false, quiet = false, no_polish = false, list_options = false, markdown = false;
};

void AddFlags(CLI::App* app, Flags* f) {
  app->add_option("--scenario", f->scenario_path, "scenario YAML (robot, terrain, start, goal)");
  app->add_option("--robot", f->robot_path, "robot YAML (or URDF)");
  app->add_option("--terrain", f->terrain_path, "terrain: .bt/.ot map, or a height map (.npy with its .yaml, or the .yaml)");
  app->add_option("--start", f->start_text, "start pose X,Y,YAW [m, m, rad]")->check(mfp::PoseFlag());
  app->add_option("--goal", f->goal_text, "goal pose X,Y,YAW [m, m, rad]")->check(mfp::PoseFlag());
  app->add_option("--max-steps", f->max_steps,
                  "new footsteps in the whole plan (default planner.max_steps; unset, route.step_budget times the "
                  "route at d_lim per configuration, at least 12 n)")
      ->check(CLI::Range(1, 100000));
  app->add_option("--window", f->window, "new footsteps per MIQP (default 2 n; the paper used 4 n)")->check(CLI::Range(1, 1000));
  app->add_option("--time-limit", f->time_limit, "time limit for the whole plan [s]")->check(mfp::FiniteRange(1e-3, 3600.0));
  app->add_option("--json", f->json_path, "write the plan JSON here ('-' = stdout)");
  app->add_option("--svg", f->svg_path, "write a picture of the plan here");
  app->add_option("--write-mps", f->mps_path, "write the first window's MIQP as free MPS (constant left out)");
  app->add_option("--relaxation-solver", f->relaxation_solver, "ipm (default: mfp's interior point, Ipopt fallback), ipopt, or dualqp (dual active set, ipm fallback)");
  app->add_option("--threads", f->threads, "branch-and-bound workers solving node relaxations at once (default 1)")
      ->check(CLI::Range(1, 64));
  app->add_flag("--validate", f->validate, "re-check the plan constraint by constraint; exit 3 on a violation");
  app->add_flag("--quiet", f->quiet, "no progress lines");
  app->add_flag("--no-polish", f->no_polish, "keep each window's MIQP plan (sin/cos by chords) instead of solving it again with exact sin/cos");
  app->add_option("--polish-time-limit", f->polish_time_limit, "time limit of the exact-trigonometry polisher per window [s]")
      ->check(mfp::FiniteRange(1e-4, 3600.0));
  app->add_flag("--list-options", f->list_options, "print every key of the YAML files (type, default, unit, description) and exit");
  app->add_flag("--markdown", f->markdown, "with --list-options: as docs/options.md");
}

// The scenario file, or the scenario the flags describe; --start and --goal override a file's.
mfp::Scenario ScenarioFromFlags(const Flags& f) {
  mfp::Scenario scenario;
  if (!f.scenario_path.empty()) {
    if (!f.robot_path.empty() || !f.terrain_path.empty()) {
      throw mfp::InputError("--scenario cannot be combined with --robot or --terrain");
    }
    scenario = mfp::LoadScenario(f.scenario_path);
    if (!f.start_text.empty()) scenario.start = ParsePose(f.start_text, "--start");
    if (!f.goal_text.empty()) scenario.goal = ParsePose(f.goal_text, "--goal");
    return scenario;
  }
  if (f.robot_path.empty() || f.terrain_path.empty() || f.start_text.empty() || f.goal_text.empty()) {
    throw mfp::InputError("give --scenario FILE, or all of --robot, --terrain, --start and --goal");
  }
  scenario.name = f.terrain_path;
  scenario.robot_path = f.robot_path;
  scenario.start = ParsePose(f.start_text, "--start");
  scenario.goal = ParsePose(f.goal_text, "--goal");
  if (!mfp::IsMapFilePath(f.terrain_path)) {  // an OctoMap or a height map
    throw mfp::InputError("--terrain " + f.terrain_path + ": expected a .bt or .ot map, or a height map (.npy with its .yaml)");
  }
  scenario.map_path = f.terrain_path;
  return scenario;
}

// Flags win over the scenario file's planner: block.
void ApplyFlags(const Flags& f, mfp::PlannerOptions* options) {
  if (!f.relaxation_solver.empty()) options->solvers.backend = mfp::ParseRelaxationBackend(f.relaxation_solver);
  if (f.threads > 0) options->solvers.threads = f.threads;
  if (f.no_polish) options->polish.enabled = false;
  if (f.polish_time_limit > 0) options->polish.time_limit_s = f.polish_time_limit;
}

mfp::PlanRequest RequestFromFlags(const Flags& f, const mfp::Scenario& scenario, const mfp::RobotModel& robot,
                                  const mfp::ScenarioTerrain& terrain, const mfp::Deadline& deadline) {
  mfp::PlanRequest request = mfp::ScenarioRequest(scenario, robot, terrain);
  if (f.max_steps > 0) request.max_steps = f.max_steps;
  if (f.window > 0) request.window_steps = f.window;
  if (f.time_limit > 0) request.time_limit_s = f.time_limit;
  request.deadline = deadline;
  return request;
}

// The first window's MIQP, exactly as the planner builds it. A rejected request (bad
// start, goal, sizes) exports nothing: PlanFootsteps answers it with its status.
void WriteFirstWindowMps(const std::string& path, const mfp::RobotModel& robot,
                         const std::vector<mfp::ConvexRegion>& regions, const mfp::PlanRequest& request,
                         const mfp::PlannerOptions& options, const Log& log) {
  if (path.empty() || !mfp::CheckPlanRequest(robot, regions, request, options).ok()) return;
  const mfp::FootstepProblem problem = mfp::FirstWindowProblem(robot, regions, request, options);
  const mfp::MiqpFormulation formulation(problem, options.formulation);
  mfp::WriteMpsFile(formulation.miqp(), "mfp", path);
  log("wrote " + path + " (" + std::to_string(formulation.miqp().num_variables()) + " columns, " +
      std::to_string(formulation.miqp().num_rows()) + " rows, " + std::to_string(formulation.miqp().num_integer()) +
      " integer)");
}

// Plans with progress lines: each window as it ends, and long windows' better plans as they go.
mfp::Plan PlanWithProgress(const mfp::RobotModel& robot, const std::vector<mfp::ConvexRegion>& regions,
                           const mfp::PlanRequest& request, mfp::PlannerOptions options, const Log& log) {
  const mfp::RelaxationSolverSet solvers = mfp::MakeRelaxationSolvers(options.solvers);
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
  return mfp::PlanFootsteps(robot, regions, request, options, solvers.workers(), [&](const mfp::PlanProgress& p) {
    windows_done = p.window;
    std::ostringstream line;
    line.precision(3);
    line << "window " << p.window << ": " << mfp::ToString(p.window_result.status) << ", " << p.steps_planned
         << " steps so far, " << p.distance_to_goal_m << " m to goal, " << p.window_result.nodes << " nodes, gap "
         << p.window_result.gap << ", " << p.elapsed_s << " s";
    log(line.str());
  });
}

std::string Summary(const mfp::Plan& plan, const mfp::RobotModel& robot) {
  std::ostringstream summary;
  summary.precision(4);
  const int steps = std::max<int>(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
  summary << "status " << mfp::ToString(plan.status) << ", " << (plan.reaches_goal ? "reaches goal" : "does NOT reach goal")
          << ", " << steps << " steps, objective " << plan.objective << ", gap " << plan.gap << ", " << plan.nodes
          << " nodes, " << plan.relaxations << " relaxations, " << plan.solve_time_s << " s";
  if (!plan.message.empty()) summary << " (" << plan.message << ")";
  return summary.str();
}

void WriteOutputs(const Flags& f, const mfp::Scenario& scenario, const mfp::Plan& plan, const mfp::RobotModel& robot,
                  const std::vector<mfp::ConvexRegion>& regions, const Log& log) {
  if (!f.json_path.empty()) {
    mfp::WriteTextOutput(f.json_path, mfp::PlanToJson(plan, robot, regions)
                                              .dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  }
  if (!f.svg_path.empty()) {
    mfp::WriteTextOutput(f.svg_path, mfp::PlanToSvg(plan, robot, regions,
                                                    {scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad},
                                                    scenario.name));
    log("wrote " + f.svg_path);
  }
}

// --validate: the plan checked constraint by constraint with exact trigonometry (no
// slack for the chords of the MIQP's sin/cos). True when every constraint holds.
bool ValidateWithExactTrigonometry(const mfp::Plan& plan, const mfp::RobotModel& robot,
                                   const std::vector<mfp::ConvexRegion>& regions, const mfp::PlannerOptions& options,
                                   const Log& log) {
  const mfp::ExactExcess excess = mfp::MeasureExactExcess(robot, regions, plan);
  std::ostringstream line;
  line.precision(3);
  line << "largest excess with exact R(yaw): reference box " << std::max(0.0, excess.reference_box_m)
       << " m, reachability box " << std::max(0.0, excess.reachability_box_m) << " m, region "
       << std::max(0.0, excess.region_m) << " m, height " << std::max(0.0, excess.height_m) << " m, yaw change "
       << std::max(0.0, excess.yaw_change_rad) << " rad";
  log(line.str());
  const auto errors = mfp::ValidatePlan(robot, regions, plan,
                                        {plan.goal_x_m, plan.goal_y_m, plan.goal_yaw_rad,
                                         options.goal_tolerance_m, options.goal_yaw_tolerance_rad},
                                        mfp::ValidationTolerances{});
  for (const std::string& e : errors) std::cerr << kProgram << ": violation: " << e << "\n";
  if (errors.empty()) log("validated: every constraint holds");
  return errors.empty();
}

int ExitCode(const Flags& f, const mfp::Plan& plan, const mfp::RobotModel& robot,
             const std::vector<mfp::ConvexRegion>& regions, const mfp::PlannerOptions& options, const Log& log) {
  using mfp::SolveStatus;
  if (plan.status == SolveStatus::kInvalidRequest || plan.status == SolveStatus::kInvalidStart ||
      plan.status == SolveStatus::kInvalidGoal || plan.status == SolveStatus::kNoMap) {
    std::cerr << kProgram << ": " << plan.message << "\n";
    return kExitBadInput;
  }
  if (f.validate && mfp::HasPlan(plan.status) &&
      !ValidateWithExactTrigonometry(plan, robot, regions, options, log)) {
    return kExitNoPlan;
  }
  if (plan.status == SolveStatus::kNoRoute || plan.status == SolveStatus::kPartial) {
    std::cerr << kProgram << ": " << plan.message << "\n";
  }
  return plan.reaches_goal ? kExitReached : kExitNoPlan;
}

// Loads, plans, writes and judges; throws InputError on bad input.
int Run(const Flags& f, const Log& log) {
  // The time limit counts from here: deriving the robot and extracting the terrain spend
  // it too (one deadline for the whole run).
  const auto run_start = std::chrono::steady_clock::now();
  mfp::Scenario scenario = ScenarioFromFlags(f);
  for (const std::string& warning : scenario.warnings) log("warning: " + warning);
  const double run_limit = f.time_limit > 0               ? f.time_limit
                           : scenario.time_limit_s > 0 ? scenario.time_limit_s
                                                       : scenario.options.default_time_limit_s;
  const mfp::Deadline run_deadline = mfp::Deadline::After(
      run_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count());
  const mfp::RobotModel robot = mfp::LoadRobot(scenario.robot_path, nullptr, run_deadline);
  const mfp::ScenarioTerrain terrain = mfp::LoadScenarioTerrain(scenario, robot, run_deadline);
  const std::vector<mfp::ConvexRegion>& regions = terrain.regions;
  if (!terrain.note.empty()) log("terrain: " + terrain.note);
  if (!terrain.body_note.empty()) log("terrain: " + terrain.body_note);
  if (terrain.map_body_obstacles) {
    log("terrain: " + std::to_string(terrain.map_body_obstacles->size()) + " body obstacles from the map");
  }
  log("robot '" + robot.name + "' (" + std::to_string(robot.num_legs()) + " legs), " +
      std::to_string(regions.size()) + " regions");
  mfp::PlannerOptions& options = scenario.options;
  ApplyFlags(f, &options);
  const mfp::PlanRequest request = RequestFromFlags(f, scenario, robot, terrain, run_deadline);
  WriteFirstWindowMps(f.mps_path, robot, regions, request, options, log);
  const mfp::Plan plan = PlanWithProgress(robot, regions, request, options, log);
  log(Summary(plan, robot));
  WriteOutputs(f, scenario, plan, robot, regions, log);
  return ExitCode(f, plan, robot, regions, options, log);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mfp-plan: multilegged footstep planning by mixed-integer convex optimisation"};
  Flags flags;
  AddFlags(&app, &flags);
  MFP_CLI_PARSE(app, argc, argv);  // a parse error exits kExitBadInput (2)
  if (flags.list_options) {
    const auto groups = mfp::OptionReference();
    std::cout << (flags.markdown ? mfp::FormatOptionsMarkdown(groups) : mfp::FormatOptionsText(groups));
    return 0;
  }
  const Log log = [&](const std::string& line) {
    if (!flags.quiet) mfp::LogLine(kProgram, line);
  };
  try {
    return Run(flags, log);
  } catch (const mfp::InputError& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const mfp::TimeLimitError& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return kExitNoPlan;
  }
}
