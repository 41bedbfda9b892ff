// The `planner:` block: every search option it names reaches PlannerOptions, and bad
// values or unknown keys are errors that name the key.
#include "io/planner_options_yaml.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "base/check.h"
#include "io/scenario_yaml.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "test_temp_path.h"
#include "tests/input_error_of.h"

namespace mfp {
namespace {

PlannerOptions Read(const std::string& text, std::vector<std::string>* warnings = nullptr) {
  PlannerOptions options;
  const std::vector<std::string> w = ReadPlannerOptions(YAML::Load(text), YamlContext{"test.yaml", "planner"}, &options);
  if (warnings != nullptr) *warnings = w;
  return options;
}

// The value of `key` in `options`, as the reference prints it.
std::string ValueOf(const PlannerOptions& options, const std::string& key) {
  for (const OptionDoc& d : DocumentOptions(PlannerOptionTable(), "", options)) {
    if (d.key == key) return d.default_value;
  }
  ADD_FAILURE() << "no key " << key;
  return "";
}

std::string Exact(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// A YAML value other than the default of option `o`.
std::string OtherValue(const Option<PlannerOptions>& o) {
  PlannerOptions defaults;
  switch (o.kind) {
    case OptionKind::kBool: return o.bool_at(defaults) ? "false" : "true";
    case OptionKind::kInt: return std::to_string(static_cast<int>(o.int_at(defaults) == o.min ? o.max : o.min));
    case OptionKind::kDouble: return Exact(o.double_at(defaults) == o.min ? o.max : o.min);
    case OptionKind::kEnum: return o.enum_names[o.enum_get(defaults) == 0 ? 1 : 0];
    case OptionKind::kNumberList: return "[0.5]";
    default: return "";
  }
}

// `section.key: value` as YAML.
std::string Nested(const std::string& key, const std::string& value) {
  const size_t dot = key.find('.');
  if (dot == std::string::npos) return key + ": " + value + "\n";
  return key.substr(0, dot) + ":\n  " + key.substr(dot + 1) + ": " + value + "\n";
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
  EXPECT_EQ(Read("relaxation_solver: dualqp\n").solvers.backend, RelaxationBackend::kDualActiveSetWithFallbacks);
  EXPECT_EQ(MakeRelaxationSolver(RelaxationBackend::kDualActiveSetWithFallbacks)->Name(), "dualqp+ipm+ipopt");
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

TEST(PlannerOptionsYaml, EveryKeyAndItsFlatAliasSetTheSameMember) {
  const PlannerOptions defaults;
  std::set<std::string> names;
  for (const Option<PlannerOptions>& o : PlannerOptionTable()) {
    EXPECT_TRUE(names.insert(o.key).second) << "twice: " << o.key;
    if (!o.alias.empty()) {
      EXPECT_TRUE(names.insert(o.alias).second) << "alias twice: " << o.alias;
    }
    const std::string value = OtherValue(o);
    ASSERT_FALSE(value.empty()) << o.key;
    std::vector<std::string> warnings;
    const PlannerOptions by_section = Read(Nested(o.key, value), &warnings);
    EXPECT_TRUE(warnings.empty()) << o.key;
    EXPECT_NE(ValueOf(by_section, o.key), ValueOf(defaults, o.key)) << o.key << " = " << value << " changed nothing";
    if (o.alias.empty()) continue;
    const PlannerOptions by_alias = Read(o.alias + ": " + value + "\n", &warnings);
    EXPECT_EQ(ValueOf(by_alias, o.key), ValueOf(by_section, o.key)) << o.alias;
    ASSERT_EQ(warnings.size(), 1u) << o.alias;
    EXPECT_NE(warnings[0].find("planner." + o.key), std::string::npos) << warnings[0];  // names the new place
  }
  EXPECT_EQ(PlannerOptionTable().size(), 110u);  // the keys of the planner: block
}

TEST(PlannerOptionsYaml, SectionsReadAsTheStructsTheyMirror) {
  std::vector<std::string> warnings;
  const PlannerOptions o = Read(
      "time_limit: 12\nsearch: {max_nodes: 77, branching: sos1}\npolish: {enabled: false, time_limit: 0.2}\n"
      "relax_and_fix: {enabled: false, time_share: 0.5}\nsolvers: {threads: 2, relaxation_solver: ipopt}\n"
      "route: {guidance: false, proposal_speeds: [0.7]}\nwindows: {max_horizon: 3}\n"
      "formulation: {yaw_encoding: big_m}\n",
      &warnings);
  EXPECT_TRUE(warnings.empty());
  EXPECT_DOUBLE_EQ(o.default_time_limit_s, 12.0);
  EXPECT_EQ(o.branch_and_bound.max_nodes, 77);
  EXPECT_EQ(o.branch_and_bound.branching, BranchingRule::kSos1Split);
  EXPECT_FALSE(o.polish.enabled);
  EXPECT_DOUBLE_EQ(o.polish.time_limit_s, 0.2);
  EXPECT_FALSE(o.relax_and_fix.enabled);
  EXPECT_DOUBLE_EQ(o.relax_and_fix.time_share, 0.5);
  EXPECT_EQ(o.solvers.threads, 2);
  EXPECT_EQ(o.solvers.backend, RelaxationBackend::kIpopt);
  EXPECT_FALSE(o.route_guidance);
  EXPECT_EQ(o.route_proposal.advance_fractions, (std::vector<double>{0.7}));
  EXPECT_EQ(o.max_horizon_windows, 3);
  EXPECT_EQ(o.formulation.yaw_encoding, YawEncoding::kBigM);
}

TEST(PlannerOptionsYaml, AKeyAndItsAliasTogetherAreRefusedNamingTheOneThatWins) {
  const std::string both = ErrorOf("max_nodes: 5\nsearch: {max_nodes: 6}\n");
  EXPECT_NE(both.find("planner.search.max_nodes"), std::string::npos) << both;
  EXPECT_NE(both.find("wins"), std::string::npos) << both;
  // The flat bool `polish` and the polish section share a name: the flat forms still read.
  std::vector<std::string> warnings;
  const PlannerOptions flat = Read("polish: false\npolish_time_limit: 0.3\n", &warnings);
  EXPECT_FALSE(flat.polish.enabled);
  EXPECT_DOUBLE_EQ(flat.polish.time_limit_s, 0.3);
  EXPECT_EQ(warnings.size(), 2u);
}

// The planner sets relax-and-fix's time and stage search for each window itself.
TEST(PlannerOptionsYaml, RelaxAndFixMembersThePlannerSetsAreRefused) {
  const std::string time = ErrorOf("relax_and_fix: {time_limit: 2}\n");
  EXPECT_NE(time.find("planner.relax_and_fix.time_share"), std::string::npos) << time;
  const std::string stage = ErrorOf("relax_and_fix: {stage: {max_nodes: 5}}\n");
  EXPECT_NE(stage.find("planner.search"), std::string::npos) << stage;
}

TEST(PlannerOptionsYaml, UnknownKeysInSectionsFailWithASuggestion) {
  const std::string typo = ErrorOf("search: {max_node: 5}\n");
  EXPECT_NE(typo.find("planner.search"), std::string::npos) << typo;
  EXPECT_NE(typo.find("did you mean 'max_nodes'"), std::string::npos) << typo;
  const std::string misplaced = ErrorOf("search: {sequential_qp: false}\n");
  EXPECT_NE(misplaced.find("planner.polish.sequential_qp"), std::string::npos) << misplaced;
  EXPECT_NE(ErrorOf("search: 3\n").find("expected a mapping"), std::string::npos);
  EXPECT_NE(ErrorOf("serch: {max_nodes: 5}\n").find("did you mean 'search'"), std::string::npos);
}

TEST(PlannerOptionsYaml, EveryKeyIsDocumented) {
  for (const OptionDoc& d : PlannerOptionDocs()) {
    EXPECT_EQ(d.key.rfind("planner.", 0), 0u) << d.key;
    EXPECT_FALSE(d.type.empty()) << d.key;
    EXPECT_FALSE(d.default_value.empty()) << d.key;
    EXPECT_FALSE(d.description.empty()) << d.key;
  }
}

// A scenario's top-level max_steps, window and time_limit are the request's: the same key
// under planner: as well would be silently replaced, so the pair is refused.
TEST(ScenarioYaml, TopLevelSizesAndTheSamePlannerKeysAreNotBothGiven) {
  const std::string path = TestTempPath("shadowed_scenario.yaml");
  const std::string base = "robot: " + std::string(MFP_SOURCE_DIR) +
                           "/config/robots/hexapod.yaml\nstart: [0, 0, 0]\ngoal: [1, 0, 0]\n"
                           "terrain: {regions: [{vertices: [[-1, -1, 0], [2, -1, 0], [2, 1, 0], [-1, 1, 0]]}]}\n";
  for (const std::string key : {"max_steps", "window", "time_limit"}) {
    std::ofstream(path) << base << key << ": 10\nplanner: {" << key << ": 20}\n";
    try {
      LoadScenario(path);
      ADD_FAILURE() << "accepted " << key << " twice";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("planner." + key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("wins"), std::string::npos) << e.what();
    }
  }
  std::ofstream(path) << base << "max_steps: 10\nplanner: {window: 8, search: {max_nodes: 9}}\n";
  const Scenario s = LoadScenario(path);
  EXPECT_EQ(s.max_steps, 10);
  EXPECT_EQ(s.options.default_window_steps, 8);
  EXPECT_EQ(s.options.branch_and_bound.max_nodes, 9);
  EXPECT_TRUE(s.warnings.empty());
  std::ofstream(path) << base << "planner: {max_nodes: 9}\n";
  const Scenario flat = LoadScenario(path);
  EXPECT_EQ(flat.options.branch_and_bound.max_nodes, 9);
  ASSERT_EQ(flat.warnings.size(), 1u);
  EXPECT_NE(flat.warnings[0].find(path), std::string::npos);  // names the file
  std::remove(path.c_str());
}

}  // namespace
}  // namespace mfp
