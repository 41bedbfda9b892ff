// mfp-bench: planner benchmark. Prints a table of
//  - single MIQPs of 12, 24 and 36 steps on the 13-region stepping stones (the sizes of
//    the seed paper's Table I), for the hexapod and the quadruped, and
//  - every scenario in config/scenarios/, planned end to end.
// With --write-instances DIR it also writes each single MIQP as NAME.mps plus its plan
// JSON (NAME.json) so bench/peers/run_peers.py can solve the identical problems.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "base/check.h"
#include "bench/course_bench.h"
#include "bench/course_digest.h"
#include "io/cli_parse.h"
#include "io/plan_json.h"
#include "io/planner_options_yaml.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/mps_writer.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/planning/request_check.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace {

struct Row {
  std::string name;
  int steps = 0;
  int integer_variables = 0;
  int nodes = 0;
  int relaxations = 0;
  double time_s = 0.0;
  double objective = 0.0;
  double worst_objective = 0.0;  // the largest over the runs (inf: a run without a plan): differs
                                 // from the first run's when a time limit cuts runs at different points
  double gap = 0.0;
  std::string status;
  bool reaches_goal = false;
  int violations = 0;
  // The lower limit: one convex QP with the first window's integer assignment fixed
  // (median of several solves) [s]; 0 when not measured.
  double fixed_qp_s = 0.0;
  // Single MIQPs: the root relaxation's gap to the final objective, and when the search
  // first held a plan within 0.5 % of its final objective [s] (median over the runs).
  double root_gap = -1.0;
  double within_s = -1.0;
  // Single MIQPs with the root cut loop on: the cut rows added and the root gap before them.
  int root_cuts = 0;
  double root_gap_before_cuts = -1.0;
  // Single MIQPs: when the search first held a plan, and when it had proven its plan
  // optimal (gap <= the search's relative_gap, status optimal; -1: not proven) [s],
  // medians over the runs, from the search's start.
  double first_plan_s = -1.0;
  double proven_s = -1.0;
  // Single MIQPs, first run: the nodes' own relaxation solves (BranchAndBoundResult::
  // node_solve_*), per node: wall time [ms] and solver iterations; -1: not measured.
  double node_solve_ms = -1.0;
  double node_iterations = -1.0;
  // QPs the solver's fallback solved (RelaxationResult::fallbacks): of the nodes' own and
  // of all the search's (first window of the first run), and over the plan; the wall time
  // of the search's [s].
  int node_fallbacks = 0, search_fallbacks = 0, plan_fallbacks = 0;
  double fallback_s = 0.0;
  // The crossover on the nodes' own QPs (search.relaxation_polish; first window, first run):
  // QPs it finished, active sets it tried.
  int node_polished = 0, node_polish_attempts = 0;
  // RINS (search.rins_frequency; first window, first run): sub-searches run, those that
  // found a better plan, and their nodes (not counted in nodes).
  int rins_runs = 0, rins_improvements = 0, rins_nodes = 0;
  // Re-certification (search.recertify_leaves), over the windows of the first run: settled
  // subtrees solved again, and of them those whose floors then met their window's gap.
  int floor_recertifications = 0, floors_certified = 0;
  // The polisher's account of each window of the first run, and the plan's largest
  // reference/reachability box excess under exact R(yaw) [m].
  std::vector<std::pair<double, mfp::PolishReport>> windows;  // (window solve time [s], report)
  double box_excess_m = 0.0;
  // The process's CPU time per run (all its threads), median over the runs [s]: on a
  // shared machine what a plan cost, where the wall time is what share of a core it got.
  double cpu_s = 0.0;
};

// Polisher rows, printed after the main tables.
std::vector<Row> g_polished;

// --print-incumbents: each better plan of the first run as it is found.
bool g_print_incumbents = false;

// The acceptance: an objective within 0.5 % of the best one.
constexpr double kAcceptance = 0.005;

void PrintHeader(const std::string& title) {
  std::printf("\n%s\n", title.c_str());
  std::printf("%-34s %6s %8s %7s %8s %9s %12s %12s %9s %-11s %5s %5s %10s %8s %9s %9s %9s %9s %8s %7s %s %s\n", "instance", "steps",
              "int_vars", "nodes", "relax", "time_s", "objective", "worst_obj", "gap", "status", "goal", "viol", "fixed_qp_s",
              "x_fixed", "root_gap", "within_s", "first_s", "proven_s", "ms_node", "it_node",
              "fallbacks", "cpu_s");
}

void PrintRow(const Row& r) {
  std::printf("%-34s %6d %8d %7d %8d %9.3f %12.4f %12.4f %9.2e %-11s %5s %5d", r.name.c_str(), r.steps,
              r.integer_variables, r.nodes, r.relaxations, r.time_s, r.objective, r.worst_objective, r.gap, r.status.c_str(),
              r.reaches_goal ? "yes" : "no", r.violations);
  if (r.fixed_qp_s > 0.0) {
    std::printf(" %10.5f %8.0f", r.fixed_qp_s, r.time_s / r.fixed_qp_s);
  } else {
    std::printf(" %10s %8s", "-", "-");
  }
  if (r.root_gap >= 0.0) {
    std::printf(" %9.2e %9.3f", r.root_gap, r.within_s);
  } else {
    std::printf(" %9s %9s", "-", "-");
  }
  for (const double s : {r.first_plan_s, r.proven_s}) {
    if (s >= 0.0) {
      std::printf(" %9.3f", s);
    } else {
      std::printf(" %9s", "-");
    }
  }
  if (r.node_solve_ms >= 0.0) {
    std::printf(" %8.3f %7.1f", r.node_solve_ms, r.node_iterations);
  } else {
    std::printf(" %8s %7s", "-", "-");
  }
  // Fallback QPs: nodes/search (first window) in their wall time, then over the plan.
  std::printf(" %d/%d/%d in %.3f s", r.node_fallbacks, r.search_fallbacks, r.plan_fallbacks, r.fallback_s);
  std::printf(" %.3f\n", r.cpu_s);
  if (r.root_cuts > 0) {
    std::printf("  %s root cut loop: %d cuts, root gap %.2e before cuts, %.2e after\n", r.name.c_str(), r.root_cuts,
                r.root_gap_before_cuts, r.root_gap);
  }
  if (r.rins_runs > 0) {
    std::printf("  %s RINS: %d sub-searches, %d better plans, %d sub-search nodes\n", r.name.c_str(), r.rins_runs,
                r.rins_improvements, r.rins_nodes);
  }
  if (r.node_polish_attempts > 0) {
    std::printf("  %s crossover: %d node QPs finished from their active sets, %d guesses tried\n", r.name.c_str(),
                r.node_polished, r.node_polish_attempts);
  }
  std::fflush(stdout);
}

// The rows whose windows re-certified floors, after the polisher's tables.
void PrintRecertifiedFloors() {
  bool header = false;
  for (const Row& r : g_polished) {
    if (r.floor_recertifications == 0) continue;
    if (!header) std::printf("\nRe-certified floors (first run, over its windows: subtrees solved again, floors certified)\n");
    header = true;
    std::printf("%-34s %6d %6d\n", r.name.c_str(), r.floor_recertifications, r.floors_certified);
  }
  std::fflush(stdout);
}

void PrintPolisherTables() {
  PrintRecertifiedFloors();
  if (g_polished.empty()) return;
  std::printf("\nPolisher per window (first run; exact sin/cos with the window's integer assignment fixed)\n");
  std::printf("%-34s %6s %9s %9s %7s %12s %12s %10s %10s %-8s %s\n", "instance", "window", "solve_s", "polish_s",
              "ratio", "obj_miqp", "obj_polish", "exc_miqp_m", "exc_pol_m", "used", "stops");
  for (const Row& r : g_polished) {
    for (size_t w = 0; w < r.windows.size(); ++w) {
      const auto& [solve_s, p] = r.windows[w];
      std::printf("%-34s %6zu %9.4f %9.4f %7.3f %12.4f %12.4f %10.2e %10.2e %-8s %s\n", r.name.c_str(), w + 1, solve_s,
                  p.time_s, p.time_s / std::max(solve_s, 1e-9), p.objective_before, p.objective_after, p.excess_before,
                  p.excess_after, !p.attempted ? "off" : p.accepted ? "yes" : "fallback", p.stops.c_str());
    }
  }
  std::printf("\nPolisher per instance (sums over windows; box_exc_m: the plan's largest box excess, exact R(yaw))\n");
  std::printf("%-34s %7s %9s %9s %7s %9s %12s %12s %10s %9s\n", "instance", "windows", "solve_s", "polish_s", "ratio",
              "max_ratio", "obj_miqp", "obj_polish", "box_exc_m", "fallbacks");
  for (const Row& r : g_polished) {
    double solve = 0.0, polish = 0.0, max_ratio = 0.0, before = 0.0, after = 0.0;
    int fallbacks = 0;
    for (const auto& [solve_s, p] : r.windows) {
      solve += solve_s;
      polish += p.time_s;
      max_ratio = std::max(max_ratio, p.time_s / std::max(solve_s, 1e-9));
      before += p.objective_before;
      after += p.objective_after;
      fallbacks += p.attempted && !p.accepted ? 1 : 0;
    }
    std::printf("%-34s %7zu %9.4f %9.4f %7.3f %9.3f %12.4f %12.4f %10.2e %9d\n", r.name.c_str(), r.windows.size(), solve,
                polish, polish / std::max(solve, 1e-9), max_ratio, before, after, r.box_excess_m, fallbacks);
  }
  std::fflush(stdout);
}

// Median time of one relaxation solve with every integer fixed to its value in x [s].
double FixedAssignmentQpTime(const mfp::Miqp& miqp, const Eigen::VectorXd& x, mfp::RelaxationBackend backend) {
  mfp::RelaxationRequest request;
  request.lower = miqp.var_lower;
  request.upper = miqp.var_upper;
  for (int j = 0; j < miqp.num_variables(); ++j) {
    if (miqp.is_integer[j]) request.lower(j) = request.upper(j) = std::round(x(j));
  }
  const auto solver = mfp::MakeRelaxationSolver(backend);
  std::vector<double> times;
  for (int k = 0; k < 21; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const mfp::RelaxationResult r = solver->Solve(miqp, request);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (r.status != mfp::RelaxationStatus::kSolved) return 0.0;  // not a lower limit then
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

Row Run(const std::string& name, const mfp::Scenario& scenario, const mfp::RobotModel& robot,
        const std::vector<mfp::ConvexRegion>& regions, const mfp::PlanRequest& request,
        const std::string& instances_dir, int repeat, bool measure_fixed_qp) {
  // The plan of the first run; the time is the median over `repeat` runs.
  std::vector<double> times, within_times, first_times, proven_times, cpu_times;
  double worst_objective = -mfp::kInfinity;
  mfp::Plan plan;
  Eigen::VectorXd first_window_x;  // the first window's MIQP solution, first run
  std::vector<std::pair<double, mfp::PolishReport>> windows;
  double root_bound = -mfp::kInfinity;
  double root_bound_before_cuts = -mfp::kInfinity;
  int root_cuts = 0;
  double node_solve_ms = -1.0, node_iterations = -1.0;
  int node_fallbacks = 0, search_fallbacks = 0, node_polished = 0, node_polish_attempts = 0;
  int rins_runs = 0, rins_improvements = 0, rins_nodes = 0;
  double fallback_s = 0.0;
  int floor_recertifications = 0, floors_certified = 0;
  for (int k = 0; k < repeat; ++k) {
    const mfp::RelaxationSolverSet solvers =
        mfp::MakeRelaxationSolvers(scenario.options.solvers);
    // Each better plan of the first window, (time [s], objective).
    std::vector<std::pair<double, double>> incumbents;
    mfp::PlannerOptions options = scenario.options;
    // The request's own clocks: wall, and the process's CPU time (on a shared machine the
    // CPU time is what the plan cost; its ratio to the wall time is the share of a core it got).
    const auto request_wall = std::chrono::steady_clock::now();
    const std::clock_t request_cpu = std::clock();
    options.branch_and_bound.on_incumbent = [&](const mfp::BranchAndBoundResult& r) {
      incumbents.emplace_back(r.solve_time_s, r.objective);
      if (g_print_incumbents && k == 0) {
        const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - request_wall).count();
        const double cpu_s = static_cast<double>(std::clock() - request_cpu) / CLOCKS_PER_SEC;
        std::printf("  %s incumbent %.4f at %.3f s, bound %.4f, gap %.2e, %d nodes; since the request %.4f s wall, "
                    "%.4f s cpu\n",
                    name.c_str(), r.objective, r.solve_time_s, r.bound, r.gap, r.nodes, wall_s, cpu_s);
      }
    };
    mfp::Plan run = mfp::PlanFootsteps(robot, regions, request, options, solvers.workers(),
                                       [&](const mfp::PlanProgress& p) {
                                         if (k == 0) {
                                           windows.emplace_back(p.window_result.solve_time_s, p.polish);
                                           floor_recertifications += p.window_result.floor_recertifications;
                                           floors_certified += p.window_result.floors_certified;
                                         }
                                         if (p.window != 1) return;
                                         if (!incumbents.empty()) first_times.push_back(incumbents.front().first);
                                         if (p.window_result.status == mfp::SolveStatus::kOptimal) {
                                           proven_times.push_back(p.window_result.solve_time_s);
                                         }
                                         if (k == 0) {
                                           first_window_x = p.window_result.x;
                                           root_bound = p.window_result.root_bound;
                                           root_bound_before_cuts = p.window_result.root_bound_before_cuts;
                                           root_cuts = p.window_result.root_cuts;
                                           const double nodes = std::max(1, p.window_result.nodes);
                                           node_solve_ms = 1e3 * p.window_result.node_solve_time_s / nodes;
                                           node_iterations = p.window_result.node_solve_iterations / nodes;
                                           node_fallbacks = p.window_result.node_fallbacks;
                                           search_fallbacks = p.window_result.fallbacks;
                                           fallback_s = p.window_result.fallback_time_s;
                                           node_polished = p.window_result.node_polished;
                                           node_polish_attempts = p.window_result.node_polish_attempts;
                                           rins_runs = p.window_result.rins_runs;
                                           rins_improvements = p.window_result.rins_improvements;
                                           rins_nodes = p.window_result.rins_nodes;
                                         }
                                         for (const auto& [t, objective] : incumbents) {
                                           if (objective <= p.window_result.objective +
                                                                kAcceptance * std::abs(p.window_result.objective)) {
                                             within_times.push_back(t);
                                             break;
                                           }
                                         }
                                       });
    times.push_back(run.solve_time_s);
    cpu_times.push_back(static_cast<double>(std::clock() - request_cpu) / CLOCKS_PER_SEC);
    worst_objective = std::max(worst_objective, mfp::HasPlan(run.status) ? run.objective : mfp::kInfinity);
    if (k == 0) plan = std::move(run);
  }
  std::sort(times.begin(), times.end());
  Row row;
  row.name = name;
  row.steps = std::max(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
  row.integer_variables = plan.integer_variables;
  row.nodes = plan.nodes;
  row.plan_fallbacks = plan.relaxation_fallbacks;
  row.relaxations = plan.relaxations;
  row.time_s = times[times.size() / 2];
  row.objective = plan.objective;
  row.worst_objective = worst_objective;
  row.gap = plan.gap;
  row.status = mfp::ToString(plan.status);
  if (request.max_windows == 1 && std::isfinite(root_bound) && !within_times.empty()) {
    row.root_gap = (plan.objective - root_bound) / std::max(1.0, std::abs(plan.objective));
    if (root_cuts > 0) {
      row.root_cuts = root_cuts;
      row.root_gap_before_cuts = (plan.objective - root_bound_before_cuts) / std::max(1.0, std::abs(plan.objective));
    }
    std::sort(within_times.begin(), within_times.end());
    row.within_s = within_times[within_times.size() / 2];
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? -1.0 : v[v.size() / 2];
  };
  if (request.max_windows == 1) {
    row.first_plan_s = median(first_times);
    // Proven only when every run proved it: a run cut short leaves it unproven.
    if (static_cast<int>(proven_times.size()) == repeat) row.proven_s = median(proven_times);
    row.node_solve_ms = node_solve_ms;
    row.node_iterations = node_iterations;
    row.node_fallbacks = node_fallbacks;
    row.search_fallbacks = search_fallbacks;
    row.fallback_s = fallback_s;
    row.node_polished = node_polished;
    row.node_polish_attempts = node_polish_attempts;
    row.rins_runs = rins_runs;
    row.rins_improvements = rins_improvements;
    row.rins_nodes = rins_nodes;
  }
  row.floor_recertifications = floor_recertifications;
  row.floors_certified = floors_certified;
  row.cpu_s = median(cpu_times);
  row.reaches_goal = plan.reaches_goal;
  row.windows = windows;
  const mfp::ExactExcess excess = mfp::MeasureExactExcess(robot, regions, plan);
  row.box_excess_m = std::max({0.0, excess.reference_box_m, excess.reachability_box_m});
  const mfp::ValidationTolerances tol;  // exact trigonometry
  row.violations = static_cast<int>(
      mfp::ValidatePlan(robot, regions, plan,
                        {scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad,
                         scenario.options.goal_tolerance_m, scenario.options.goal_yaw_tolerance_rad},
                        tol)
          .size());
  // The first window's MIQP: its fixed-assignment QP time and its export.
  const bool fixed_qp = measure_fixed_qp && first_window_x.size() > 0;
  if ((fixed_qp || !instances_dir.empty()) && mfp::CheckPlanRequest(robot, regions, request, scenario.options).ok()) {
    const mfp::MiqpFormulation formulation(mfp::FirstWindowProblem(robot, regions, request, scenario.options),
                                           scenario.options.formulation);
    if (fixed_qp) {
      row.fixed_qp_s = FixedAssignmentQpTime(formulation.miqp(), first_window_x, scenario.options.solvers.backend);
    }
    if (!instances_dir.empty()) {
      mfp::WriteMpsFile(formulation.miqp(), name, instances_dir + "/" + name + ".mps");
      std::ofstream(instances_dir + "/" + name + ".json") << mfp::PlanToJson(plan, robot, regions).dump(1) << "\n";
    }
  }
  return row;
}

}  // namespace

// Applies KEY=VALUE overrides to a scenario's planner options (the keys and checks of
// the planner: block; KEY may name a section, search.max_nodes), so that one command
// measures one variant.
void ApplyOverrides(const std::vector<std::string>& overrides, mfp::Scenario* scenario) {
  if (overrides.empty()) return;
  YAML::Node node;
  for (const std::string& kv : overrides) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos) throw mfp::InputError("--set " + kv + ": expected KEY=VALUE");
    const std::string key = kv.substr(0, eq);
    const size_t dot = key.find('.');
    if (dot == std::string::npos) {
      node[key] = YAML::Load(kv.substr(eq + 1));
    } else {
      node[key.substr(0, dot)][key.substr(dot + 1)] = YAML::Load(kv.substr(eq + 1));
    }
  }
  for (const std::string& warning : mfp::ReadPlannerOptions(node, {"--set", ""}, &scenario->options)) {
    std::cerr << "mfp-bench: warning: " << warning << "\n";
  }
}

int main(int argc, char** argv) {
  CLI::App app{"mfp-bench: Table I sizes and every scenario, planned with mfp's solver"};
  std::string scenario_dir = std::string(MFP_SOURCE_DIR) + "/config/scenarios";
  std::string instances_dir;
  double time_limit = 60.0;
  bool table_only = false, scenarios_only = false;
  std::vector<int> sizes = {12, 24, 36};
  std::vector<std::string> overrides;
  int repeat = 1;
  std::vector<std::string> table_robots = {"hexapod", "littledog"};
  app.add_option("--scenarios", scenario_dir, "folder of scenario YAML files");
  app.add_option("--time-limit", time_limit, "time limit per instance [s]")->check(CLI::Range(0.01, 3600.0));
  app.add_option("--sizes", sizes, "single-MIQP sizes (new steps)");
  app.add_option("--write-instances", instances_dir, "write NAME.mps + NAME.json of each single MIQP here");
  app.add_option("--set", overrides, "planner option KEY=VALUE, as in a scenario's planner: block, e.g. search.max_nodes=100 (docs/options.md; repeatable)");
  app.add_option("--repeat", repeat, "runs per instance; the time printed is their median")->check(CLI::Range(1, 1000));
  app.add_flag("--table-only", table_only, "only the single MIQPs of Table I");
  app.add_option("--table-robots", table_robots, "Table I robots, of hexapod and littledog (default both)")
      ->check(CLI::IsMember({"hexapod", "littledog"}));
  app.add_flag("--print-incumbents", g_print_incumbents, "print each better plan of a run's first window as found");
  app.add_flag("--scenarios-only", scenarios_only, "only the scenarios");
  int courses = 0;
  uint64_t course_seed = 1;
  double course_time_limit = 15.0;
  std::string write_courses;
  app.add_option("--courses", courses, "plan N generated courses (4, 6 and 8 legs) and judge them against their boxes")
      ->check(CLI::Range(1, 100000));
  app.add_option("--course-seed", course_seed, "seed of the first generated course (course i uses seed + i)");
  app.add_option("--course-time-limit", course_time_limit, "time limit per generated course [s]")
      ->check(CLI::Range(0.01, 3600.0));
  bool course_top_faces = false;
  app.add_flag("--course-top-faces", course_top_faces,
               "generated courses: plan on the boxes' true top faces inset by the edge margin, not extracted regions");
  int course_first = 0;
  app.add_option("--course-first", course_first, "generated courses: start at this index (to re-run one course of a sample)");
  bool course_windows = false;
  app.add_flag("--course-windows", course_windows, "generated courses: one line per window (size, binaries, nodes, time)");
  app.add_option("--write-courses", write_courses, "write each generated course as a scenario YAML here");
  std::string course_plans;
  app.add_option("--course-plans", course_plans, "write each generated course's plan JSON (NAME.json) here");
  std::string course_only;
  bool course_verbose = false;
  bool no_body_check = false;
  app.add_flag("--no-body-check", no_body_check,
               "generated courses: give the planner no body obstacles (the checker still judges the body)");
  app.add_option("--course-only", course_only, "generated courses: plan only those whose name contains this text; a kind's name (e.g. doorway) "
                 "makes every course of that kind");
  app.add_flag("--course-verbose", course_verbose, "generated courses: print each accepted window");
  bool course_digest = false;
  app.add_flag("--course-digest", course_digest,
               "generated courses: only generate them and print a digest of each (equal digests, equal courses)");
  std::vector<std::string> course_robots;
  app.add_option("--course-robots", course_robots,
                 "generated courses: robot files (YAML or URDF) to cycle through (default: config/robots' littledog, "
                 "hexapod, octopod)")
      ->check(CLI::ExistingFile);
  std::vector<std::string> course_extra_robots;
  app.add_option("--course-extra-robots", course_extra_robots,
                 "generated courses: robot files (YAML or URDF, e.g. the zoo's Go1 and ANYmal C) added to the "
                 "rotation after --course-robots' (or the default three)")
      ->check(CLI::ExistingFile);
  MFP_CLI_PARSE(app, argc, argv);
  try {
    if (courses > 0) {
      mfp::CourseBenchOptions o;
      o.courses = courses;
      o.seed = course_seed;
      o.time_limit_s = course_time_limit;
      o.robots_dir = std::string(MFP_SOURCE_DIR) + "/config/robots";
      o.robot_paths = course_robots;
      o.extra_robot_paths = course_extra_robots;
      o.write_dir = write_courses;
      o.plan_dir = course_plans;
      o.top_face_regions = course_top_faces;
      o.only = course_only;
      o.body_check = !no_body_check;
      o.verbose = course_verbose;
      o.print_windows = course_windows;
      o.first = course_first;
      o.adjust = [&](mfp::Scenario* s) { ApplyOverrides(overrides, s); };
      if (course_digest) {
        mfp::PrintCourseDigests(o);
      } else {
        mfp::RunCourseBench(o);
      }
      return 0;
    }
    if (!instances_dir.empty()) std::filesystem::create_directories(instances_dir);
    if (!scenarios_only) {
      PrintHeader("Single MIQPs on the 13-region stepping stones (seed paper Table I: 12/24/36 steps, 312/552/828 "
                  "integer variables, 0.08/0.44/3.68 s with Gurobi)");
      for (const std::string& robot_name : table_robots) {
        mfp::Scenario scenario = mfp::LoadScenario(scenario_dir + "/" + robot_name + "_stepping_stones_45.yaml");
        ApplyOverrides(overrides, &scenario);
        const mfp::RobotModel robot = mfp::LoadRobot(scenario.robot_path);
        const std::vector<mfp::ConvexRegion> regions = mfp::ScenarioRegions(scenario, robot);
        for (int steps : sizes) {
          mfp::PlanRequest request = mfp::ScenarioRequest(scenario, robot, regions);
          request.max_steps = steps;
          request.window_steps = steps;
          request.time_limit_s = time_limit;
          request.max_windows = 1;  // one MIQP, as in Table I
          const Row row = Run(robot_name + "_stones_" + std::to_string(steps), scenario, robot, regions, request,
                              instances_dir, repeat, /*measure_fixed_qp=*/true);
          PrintRow(row);
          g_polished.push_back(row);
        }
      }
    }
    if (!table_only) {
      PrintHeader("Scenarios planned end to end (default windows of 2 n steps)");
      std::vector<std::string> files;
      for (const auto& entry : std::filesystem::directory_iterator(scenario_dir)) {
        if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
      }
      std::sort(files.begin(), files.end());
      for (const std::string& file : files) {
        mfp::Scenario scenario = mfp::LoadScenario(file);
        ApplyOverrides(overrides, &scenario);
        const mfp::RobotModel robot = mfp::LoadRobot(scenario.robot_path);
        const std::vector<mfp::ConvexRegion> regions = mfp::ScenarioRegions(scenario, robot);
        mfp::PlanRequest request = mfp::ScenarioRequest(scenario, robot, regions);
        if (request.time_limit_s <= 0) request.time_limit_s = time_limit;
        const Row row = Run(std::filesystem::path(file).stem().string(), scenario, robot, regions, request, "", repeat,
                            /*measure_fixed_qp=*/false);
        PrintRow(row);
        g_polished.push_back(row);
      }
    }
    PrintPolisherTables();
  } catch (const mfp::InputError& e) {
    std::cerr << "mfp-bench: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
