#include "planner/planning/internal/relax_and_fix.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <thread>
#include <utility>
#include <vector>

#include "base/check.h"
#include "base/deadline.h"
#include "planner/qp/fixed_integer_qp.h"

namespace mfp {
namespace {

// The integer variables of each configuration: its yaw segments and body regions, and
// the region and trim binaries of its steps.
std::vector<std::vector<int>> IntegersByConfiguration(const MiqpFormulation& f) {
  const FootstepVariables& v = f.vars();
  std::vector<std::vector<int>> integers(f.num_configurations());
  for (int cfg = 0; cfg < f.num_configurations(); ++cfg) {
    for (int s : v.segment[cfg]) integers[cfg].push_back(s);
    for (int g : v.body_region[cfg]) integers[cfg].push_back(g);
  }
  for (int i = f.num_legs(); i < f.num_steps(); ++i) {
    std::vector<int>& members = integers[f.ConfigurationOfStep(i)];
    for (int h : v.region[i]) {
      if (h >= 0) members.push_back(h);
    }
    if (v.trim[i] >= 0) members.push_back(v.trim[i]);
  }
  return integers;
}

// Each variable's configuration in IntegersByConfiguration's grouping; -1 for the others.
std::vector<int> ConfigurationOf(const std::vector<std::vector<int>>& integers, int num_variables) {
  std::vector<int> configuration_of(num_variables, -1);
  for (size_t cfg = 0; cfg < integers.size(); ++cfg) {
    for (int j : integers[cfg]) configuration_of[j] = static_cast<int>(cfg);
  }
  return configuration_of;
}

// Out of time before the last stage: the integers still open are rounded along the plan
// from the latest stage's solution x (earlier configurations keep their fixed values,
// which that solution holds), and the best of `proposals` (such roundings) whose QP is
// feasible becomes the plan. One QP per proposal, so a short time limit still ends with
// a complete plan. Its QPs and their fallbacks are counted in *result.
std::optional<Eigen::VectorXd> CompleteByRounding(const MiqpFormulation& formulation,
                                                  const std::vector<Eigen::VectorXd>& proposals,
                                                  const Eigen::VectorXd& x, RelaxationSolver& solver,
                                                  const Deadline& deadline, double feasibility_tolerance,
                                                  RelaxAndFixResult* result) {
  RelaxationRequest request;
  request.warm_start = x;
  request.deadline = deadline;
  FixedAssignmentOptions options;
  options.feasibility_tolerance = feasibility_tolerance;
  return BestFixedAssignment(formulation.miqp(), proposals, solver, request, options, &result->relaxations,
                             &result->fallbacks);
}

}  // namespace

RelaxAndFixResult RelaxAndFix(const MiqpFormulation& formulation, const std::vector<RelaxationSolver*>& solvers,
                              const RelaxAndFixOptions& options) {
  MFP_CHECK(options.lookahead_configurations >= 0 && options.nodes_per_stage >= 1 && options.max_searched_stages >= 0);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const Miqp& full = formulation.miqp();
  const std::vector<std::vector<int>> integers = IntegersByConfiguration(formulation);
  const int B = formulation.num_configurations();
  const RoundingHeuristic rounding = [&formulation](const Eigen::VectorXd& relaxed) {
    return formulation.RoundAlongPlan(relaxed);
  };

  RelaxAndFixResult result;
  const std::vector<int> configuration_of = ConfigurationOf(integers, full.num_variables());
  // The earlier stages' choices, as bounds on the full model's variables.
  Eigen::VectorXd fixed_lower = full.var_lower, fixed_upper = full.var_upper;
  Eigen::VectorXd x;
  const auto complete_by_rounding = [&] {
    if (x.size() == 0) return;
    // The completion is what turns the stages' choices into a plan: its QPs run under the
    // caller's deadline (not under the time limit that has just ended the stages),
    // extended by completion_overrun_s (the deadline may be what ended them).
    result.x = CompleteByRounding(formulation, formulation.RoundAlongPlan(x), x, *solvers.front(),
                                  options.stage.deadline.ExtendedBy(options.completion_overrun_s),
                                  options.stage.feasibility_tolerance, &result);
    result.completed_by_rounding = result.x.has_value();
  };
  // Stages for the configurations that have integers; the last stage takes all the rest.
  for (int cfg = 1; cfg < B; ++cfg) {
    const double remaining = options.time_limit_s - elapsed();
    if (remaining <= 0.0 || (options.max_searched_stages > 0 && result.stages >= options.max_searched_stages)) {
      complete_by_rounding();
      return result;
    }
    const int last_integer_configuration = cfg + options.lookahead_configurations;
    const bool final_stage = last_integer_configuration >= B - 1;
    Miqp stage = options.hull_for_later_steps && !final_stage
                     ? formulation.WithRegionsRelaxedFrom((last_integer_configuration + 1) * formulation.num_legs())
                     : full;
    for (int j = 0; j < full.num_variables(); ++j) {
      if (!full.is_integer[j]) continue;
      stage.is_integer[j] = final_stage || configuration_of[j] <= last_integer_configuration;
      if (configuration_of[j] < cfg) {
        stage.var_lower(j) = fixed_lower(j);
        stage.var_upper(j) = fixed_upper(j);
      }
    }
    // Branch only on groups whose members are integer in this stage.
    stage.sos1_groups.clear();
    for (const std::vector<int>& group : full.sos1_groups) {
      if (stage.is_integer[group.front()]) stage.sos1_groups.push_back(group);
    }
    BranchAndBoundOptions bnb = options.stage;
    bnb.max_nodes = options.nodes_per_stage;
    bnb.relative_gap = options.stage_relative_gap;
    bnb.rounding_heuristic = bnb.rounding_heuristic && options.stage_rounding;
    if (!final_stage) bnb.relaxation_tolerance = std::max(bnb.relaxation_tolerance, options.stage_relaxation_tolerance);
    // A stage may take half of what is left: the later stages are the larger searches
    // (more of the plan's cost is decided there), so an even split starved them and their
    // searches stopped at a poor incumbent (docs/measurements.md).
    bnb.time_limit_s = final_stage ? remaining : 0.5 * remaining;
    bnb.on_incumbent = nullptr;
    bnb.first_plan_overrun_s = 0.0;  // what may overrun the deadline is the completion (completion_overrun_s)
    bnb.root_heuristic = nullptr;  // a stage is itself part of the root heuristic
    bnb.first_plan_heuristic = nullptr;
    bnb.root_cut_rounds = 0;  // the stages are heuristics: the cut loop is the full search's
    // So are group probing, RINS and re-certification: a stage (relax-and-fix's dive gives a window's first
    // plan) spends no time on a stronger bound or on improving its own plans.
    bnb.group_probing = false;
    bnb.rins_frequency = 0;
    bnb.recertify_leaves = 0;
    bnb.recertify_within = nullptr;  // it refers to the window's MIQP, not the stage's
    const BranchAndBoundResult r = SolveBranchAndBound(stage, solvers, bnb, rounding);
    ++result.stages;
    result.nodes += r.nodes;
    result.relaxations += r.relaxations;
    result.fallbacks += r.fallbacks;
    if (r.x.size() == 0) {  // earlier choices left no plan, or the stage's limits came first
      if (r.status != SolveStatus::kInfeasible) complete_by_rounding();
      return result;
    }
    x = r.x;
    if (final_stage) break;
    for (int j : integers[cfg]) {  // fix this configuration's choices
      fixed_lower(j) = fixed_upper(j) = std::round(x(j));
    }
  }
  if (x.size() == 0) return result;
  for (int j = 0; j < full.num_variables(); ++j) {
    if (full.is_integer[j]) x(j) = std::round(x(j));
  }
  if (full.MaxViolation(x) > options.stage.feasibility_tolerance) return result;
  result.x = x;
  return result;
}

RelaxAndFixResult RoundingDive(const MiqpFormulation& formulation, RelaxationSolver& solver,
                               const Eigen::VectorXd& root_x, const RelaxAndFixOptions& options) {
  const Miqp& full = formulation.miqp();
  MFP_CHECK(root_x.size() == full.num_variables());
  const std::vector<int> configuration_of =
      ConfigurationOf(IntegersByConfiguration(formulation), full.num_variables());
  const int B = formulation.num_configurations();
  const double tolerance = options.stage.feasibility_tolerance;
  // The stages' QPs end at the dive's share (time_limit_s) or the caller's deadline,
  // whichever comes first; the completion of a dive cut short runs under the caller's,
  // extended by completion_overrun_s.
  const Deadline share = options.stage.deadline.Within(options.time_limit_s);
  const Deadline completion = options.stage.deadline.ExtendedBy(options.completion_overrun_s);
  RelaxAndFixResult result;
  Eigen::VectorXd x = root_x;
  int completed_stages = 0;
  // Cut short by the share after at least one stage was completed: the rest is rounded
  // along the plan from the latest stage's point (`proposals`: its roundings, less those a
  // stage QP already judged), as RelaxAndFix's stages are. Before the first stage there is
  // nothing to complete: x's roundings are the root's.
  const auto complete_by_rounding = [&](const std::vector<Eigen::VectorXd>& proposals) {
    if (completed_stages == 0 || completion.Expired()) return;
    result.x = CompleteByRounding(formulation, proposals, x, solver, completion, tolerance, &result);
    result.completed_by_rounding = result.x.has_value();
  };
  for (int cfg = 1; cfg < B; ++cfg) {
    if (share.Expired()) {
      complete_by_rounding(formulation.RoundAlongPlan(x));
      return result;
    }
    const bool final_stage = cfg == B - 1;
    // Configurations up to cfg integer (the earlier ones fixed to their values in x), the
    // next one's region choices relaxed and the steps after it in their regions' hull: the
    // completion of this stage's choice is also the relaxation of the next stage, whose
    // choice is rounded from it.
    Miqp stage = formulation.WithRegionsRelaxedFrom((cfg + 2) * formulation.num_legs());
    for (int j = 0; j < full.num_variables(); ++j) {
      if (!full.is_integer[j]) continue;
      stage.is_integer[j] = configuration_of[j] <= cfg;
      if (configuration_of[j] < cfg) stage.var_lower(j) = stage.var_upper(j) = std::round(x(j));
    }
    RelaxationRequest request;
    request.warm_start = x;
    request.deadline = share;
    request.relative_tolerance = options.stage.relaxation_tolerance;
    if (!final_stage) request.relative_tolerance = std::max(request.relative_tolerance, options.stage_relaxation_tolerance);
    ++result.stages;
    // The proposals rounded from x, each completed by a QP; the first one completed becomes
    // x. A QP that ends unsolved once the share has passed was cut short: neither it nor
    // the proposals after it were judged.
    std::vector<Eigen::VectorXd> proposals = formulation.RoundAlongPlan(x);
    size_t judged = 0;
    bool completed = false, cut_short = false;
    for (; judged < proposals.size(); ++judged) {
      RelaxationResult r = SolveWithIntegersFixed(stage, proposals[judged], solver, request);
      ++result.relaxations;
      result.fallbacks += r.fallbacks;
      if (r.status == RelaxationStatus::kSolved) {
        x = std::move(r.x);
        completed = true;
        break;
      }
      if (r.status != RelaxationStatus::kInfeasible && share.Expired()) {
        cut_short = true;
        break;
      }
    }
    if (!completed) {
      // Cut short, the stages so far are completed with the roundings not yet judged; when
      // every rounding failed on its own the stage's choice is what failed (its roundings
      // would fail in the completion too): no plan.
      if (cut_short) {
        proposals.erase(proposals.begin(), proposals.begin() + static_cast<std::ptrdiff_t>(judged));
        complete_by_rounding(proposals);
      }
      return result;
    }
    ++completed_stages;
  }
  if (B > 1 && full.MaxViolation(x) <= tolerance) result.x = x;
  return result;
}

RelaxAndFixOptions DiveOptions(RelaxAndFixOptions options) {
  options.nodes_per_stage = 1;
  options.stage_rounding = true;
  options.stage.rounding_heuristic = true;
  options.stage.rounding_stops_at_first_plan = true;
  options.stage.branching = BranchingRule::kGroupOrder;
  return options;
}

RelaxAndFixResult RelaxAndFixTwoPaths(const MiqpFormulation& formulation,
                                      const std::vector<RelaxationSolver*>& solvers,
                                      const RelaxAndFixOptions& options) {
  if (solvers.size() < 2) return RelaxAndFix(formulation, solvers, options);
  RelaxAndFixOptions second = options;
  second.stage_relaxation_tolerance = 0.0;
  RelaxAndFixResult other;
  std::thread thread([&] { other = RelaxAndFix(formulation, {solvers[1]}, second); });
  RelaxAndFixResult result = RelaxAndFix(formulation, {solvers[0]}, options);
  thread.join();
  const Miqp& full = formulation.miqp();
  const bool other_better =
      other.x && (!result.x || full.Objective(*other.x) < full.Objective(*result.x));
  if (other_better) {
    result.x = other.x;
    result.completed_by_rounding = other.completed_by_rounding;
  }
  result.stages += other.stages;
  result.nodes += other.nodes;
  result.relaxations += other.relaxations;
  result.fallbacks += other.fallbacks;
  return result;
}

}  // namespace mfp
