// The `planner:` block: every search option it names reaches PlannerOptions, and bad
// values or unknown keys are errors that name the key.
#include "planner/io/planner_options_yaml.h"

#include <gtest/gtest.h>

#include <string>

#include "planner/base/check.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/input_error_of.h"

namespace mfp {
namespace {

PlannerOptions Read(const std::string& text) {
  PlannerOptions options;
  ReadPlannerOptions(YAML::Load(text), YamlContext{"test.yaml", "planner"}, &options);
  return options;
}

std::string ErrorOf(const std::string& text) {
  return InputErrorOf([&] { Read(text); });
}

TEST(PlannerOptionsYaml, SearchOptionsReachTheBranchAndBound) {
  const PlannerOptions o = Read(
      "threads: 2\nbranching: reliability\nnode_selection: plunging\nrelative_gap: 0.005\n"
      "reliability: 3\nstrong_branching_candidates: 5\nstrong_branching_lookahead: 2\nplunge_fraction: 0.25\n");
  EXPECT_EQ(o.solvers.threads, 2);
  EXPECT_EQ(o.branch_and_bound.branching, BranchingRule::kReliability);
  EXPECT_EQ(o.branch_and_bound.node_selection, NodeSelection::kBestBoundWithPlunging);
  EXPECT_DOUBLE_EQ(o.branch_and_bound.relative_gap, 0.005);
  EXPECT_EQ(o.branch_and_bound.reliability, 3);
  EXPECT_EQ(o.branch_and_bound.strong_branching_candidates, 5);
  EXPECT_EQ(o.branch_and_bound.strong_branching_lookahead, 2);
  EXPECT_DOUBLE_EQ(o.branch_and_bound.plunge_fraction, 0.25);
}

TEST(PlannerOptionsYaml, SolverKeysReachTheSolverOptions) {
  const PlannerOptions o = Read("relaxation_solver: ipopt\nthreads: 3\n");
  EXPECT_EQ(o.solvers.backend, RelaxationBackend::kIpopt);
  EXPECT_EQ(o.solvers.threads, 3);
  EXPECT_EQ(MakeRelaxationSolvers(o.solvers).workers().size(), 3u);
  const std::string bad = ErrorOf("relaxation_solver: gurobi\n");
  EXPECT_NE(bad.find("relaxation_solver"), std::string::npos);
  EXPECT_NE(bad.find("ipm, ipopt"), std::string::npos);  // lists what is allowed
}

TEST(PlannerOptionsYaml, FormulationAndHeuristicOptionsArrive) {
  const PlannerOptions o = Read(
      "clip_yaw_to_reach: false\nreduced_cost_fixing: false\nearly_cutoff: false\nrelax_and_fix: false\n"
      "relax_and_fix_time_share: 0.5\nrelax_and_fix_min_configurations: 6\nrelax_and_fix_region_hull: false\n"
      "relax_and_fix_stage_tolerance: 0\nsnap_yaw_segments: false\n"
      "relax_and_fix_two_paths: false\nrelax_and_fix_stage_rounding: true\n"
      "polish: false\npolish_time_limit: 0.25\ntrimmed_configurations_hold_yaw: false\n");
  EXPECT_FALSE(o.formulation.clip_yaw_to_reach);
  EXPECT_FALSE(o.branch_and_bound.reduced_cost_fixing);
  EXPECT_FALSE(o.branch_and_bound.early_cutoff);
  EXPECT_FALSE(o.relax_and_fix.enabled);
  EXPECT_DOUBLE_EQ(o.relax_and_fix.time_share, 0.5);
  EXPECT_EQ(o.relax_and_fix.min_configurations, 6);
  EXPECT_FALSE(o.relax_and_fix.hull_for_later_steps);
  EXPECT_EQ(o.relax_and_fix.stage_relaxation_tolerance, 0.0);
  EXPECT_FALSE(o.snap_yaw_segments);
  EXPECT_FALSE(o.relax_and_fix.two_paths);
  EXPECT_TRUE(o.relax_and_fix.stage_rounding);
  EXPECT_FALSE(o.polish.enabled);
  EXPECT_DOUBLE_EQ(o.polish.time_limit_s, 0.25);
  EXPECT_FALSE(o.formulation.trimmed_configurations_hold_yaw);
  EXPECT_NE(ErrorOf("polish_time_limit: 0\n").find("polish_time_limit"), std::string::npos);
  EXPECT_NE(ErrorOf("relax_and_fix_stage_tolerance: 0.1\n").find("relax_and_fix_stage_tolerance"), std::string::npos);
  EXPECT_NE(ErrorOf("relax_and_fix_time_share: 0\n").find("relax_and_fix_time_share"), std::string::npos);
  EXPECT_NE(ErrorOf("relax_and_fix_min_configurations: 1\n").find("relax_and_fix_min_configurations"),
            std::string::npos);
}

TEST(PlannerOptionsYaml, DefaultsStayWhenAbsent) {
  const PlannerOptions defaults;
  const PlannerOptions o = Read("max_steps: 10\n");
  EXPECT_EQ(o.solvers.threads, defaults.solvers.threads);
  EXPECT_EQ(o.branch_and_bound.branching, defaults.branch_and_bound.branching);
  EXPECT_EQ(o.default_max_steps, 10);
}

TEST(PlannerOptionsYaml, RouteGuidanceKeysArrive) {
  const PlannerOptions o = Read(
      "route_proposals: false\nroute_proposal_speeds: [0.8, 0.4]\nroute_proposal_yaw_rate: 0.5\n"
      "window_stall_fraction: 0.1\nroute_step_budget: 4\n");
  EXPECT_FALSE(o.route_proposals);
  EXPECT_EQ(o.route_proposal.advance_fractions, (std::vector<double>{0.8, 0.4}));
  EXPECT_DOUBLE_EQ(o.route_proposal.yaw_rate_fraction, 0.5);
  EXPECT_DOUBLE_EQ(o.window_stall_fraction, 0.1);
  EXPECT_DOUBLE_EQ(o.route_step_budget, 4.0);
  EXPECT_NE(ErrorOf("route_proposal_speeds: [0.5, 0]\n").find("route_proposal_speeds"), std::string::npos);
  EXPECT_NE(ErrorOf("route_proposal_speeds: fast\n").find("route_proposal_speeds"), std::string::npos);
}

TEST(PlannerOptionsYaml, BadValuesNameTheKey) {
  EXPECT_NE(ErrorOf("threads: 0\n").find("threads"), std::string::npos);
  EXPECT_NE(ErrorOf("threads: 65\n").find("threads"), std::string::npos);
  const std::string branching = ErrorOf("branching: strongest\n");
  EXPECT_NE(branching.find("branching"), std::string::npos);
  EXPECT_NE(branching.find("reliability"), std::string::npos);  // lists what is allowed
  EXPECT_NE(ErrorOf("node_selection: random\n").find("plunging"), std::string::npos);
  EXPECT_NE(ErrorOf("thread: 2\n").find("thread"), std::string::npos);  // a typo is not ignored
}

}  // namespace
}  // namespace mfp
