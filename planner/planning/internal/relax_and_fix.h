#pragma once
// Relax-and-fix along the plan: a primal heuristic for the footstep MIQP that decides
// the integers configuration by configuration. Stage b solves the whole MIQP by a small
// branch-and-bound in which only the integers of configurations b .. b + lookahead are
// integer (those of earlier configurations are fixed to the earlier stages' choices,
// later ones are relaxed), then fixes configuration b's choices. The last stage leaves
// no integer relaxed, so its solution is a feasible plan of the whole MIQP.
//
// Every stage sees the whole horizon through the relaxation of the later steps, so the
// early choices are made for the goal, not greedily; each stage is about as hard as
// a 2-configuration window. Used to seed the search with a good incumbent.
//
// Anytime: when the time runs out before the last stage, the configurations still open
// are rounded along the plan from the latest stage's solution, so a short budget ends
// with a complete (if worse) plan rather than none. The rounding's QPs (one per proposal)
// run under the caller's deadline, stage.deadline, extended by completion_overrun_s:
// time_limit_s, or that deadline itself, has passed by then.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/qp/relaxation_solver.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

// Defaults chosen on the Table I instances (docs/measurements.md): no lookahead (keeping
// later configurations integer makes each stage a bigger search that ends at its node
// limit with worse choices), and a stage gap coarser than the search's, which gives the
// same plans sooner.
struct RelaxAndFixOptions {
  int lookahead_configurations = 0;          // configurations kept integer beyond the one being fixed
  int nodes_per_stage = 100;         // branch-and-bound nodes per stage
  double stage_relative_gap = 0.005;  // a stage's search stops this close to its optimum
  double time_limit_s = 1.0;         // whole heuristic [s]; past it, the rest is rounded
  // The completion's QPs (the rounding of what was not searched) may run this long past
  // stage.deadline [s] (its stop flag still ends them): when that deadline is what ended
  // the stages, a completion under it alone has no time and the stages' choices no plan.
  double completion_overrun_s = 0.0;
  int max_searched_stages = 0;       // stages searched before the rest is rounded (0: all)
  // The steps after the stage's integer configurations choose no region: each stands in
  // the convex hull of its regions (MiqpFormulation::WithRegionsRelaxedFrom) instead of
  // the continuous relaxation of the region binaries. Smaller stage QPs.
  bool hull_for_later_steps = true;
  // Relative accuracy of the QPs of every stage but the last: a stage keeps a choice
  // within stage_relative_gap, far coarser. The last stage, whose point is the plan,
  // keeps the solver's own accuracy.
  double stage_relaxation_tolerance = 1e-6;
  // Run the search's rounding heuristic inside the stages. Off: its QPs (integers fixed
  // to a rounding, warm-started from a fractional point) were a fifth of the heuristic's
  // work on Table I, and the plans came out the same without them (docs/measurements.md). A stage
  // out of time before its first leaf still ends rounded (completed_by_rounding).
  bool stage_rounding = false;
  BranchAndBoundOptions stage;       // other search options of each stage

  // How PlanFootsteps uses it: each window's search is seeded with a relax-and-fix plan
  // when enabled and the window has at least min_configurations configurations of new
  // steps (on fewer, relax-and-fix is nearly the search itself: the 2-configuration
  // default windows and 12-step MIQPs solve faster without), given time_share of the
  // window's time. The whole time by default: relax-and-fix rounds what it has not
  // searched when the time runs out, and on Table I its plans at any budget beat the
  // search's (docs/measurements.md). With two or more workers and two_paths, two
  // single-worker runs (RelaxAndFixTwoPaths) instead of one run whose stage searches
  // share the workers.
  bool enabled = true;
  double time_share = 1.0;
  int min_configurations = 4;
  bool two_paths = true;
  // A window whose root roundings gave a plan within wait_gap of the root bound runs the
  // seed only after its search has processed after_nodes nodes without ending
  // (BranchAndBoundOptions::root_heuristic_after_nodes and root_heuristic_wait_gap;
  // after_nodes 0: at the root; wait_gap 1e9: any plan waits). "Root roundings" include
  // the quick first-plan dive. A search that proves its window within after_nodes does
  // without the seed's cost; a poorer root plan gets the seed's plan at once, as the
  // anytime plan of a long search (figures: docs/measurements.md, "hexproof7").
  int after_nodes = 200;
  double wait_gap = 0.3;
  // A seeded window whose root roundings find no plan first gets a quick one: a dive,
  // relax-and-fix with one node per stage and the stage roundings on (each stage's
  // configuration fixed from its root relaxation's best rounding), before the full run
  // above. On Table I's LittleDog 36 no rounding of the root is feasible, and the full
  // run's plan came after seconds (docs/measurements.md).
  bool first_plan_dive = true;
  // The dive with one QP per stage: stage b's configuration is rounded
  // (MiqpFormulation::RoundAlongPlan) from stage b - 1's point (the first from the root
  // relaxation's), and one QP completes it with the earlier configurations fixed, the next
  // one's region choices relaxed and the later steps in their regions' hull. That QP is both
  // the choice's feasibility check and the next stage's relaxation, where the stage-search
  // dive solves a relaxation and a rounding per stage (RoundingDive; docs/measurements.md).
  // When a stage's roundings all fail, the stage-search dive runs.
  bool rounding_dive = true;
};

struct RelaxAndFixResult {
  std::optional<Eigen::VectorXd> x;  // a feasible point of formulation.miqp(), if found
  int stages = 0;
  int nodes = 0;
  int relaxations = 0;
  int fallbacks = 0;  // of the relaxations, those solved by the solver's fallback
  // Stopped before the last stage (time, max_searched_stages, or a stage's own limits):
  // the configurations left were rounded along the plan from the last stage's solution
  // instead of searched.
  bool completed_by_rounding = false;
};

// options turned into the quick dive of RelaxAndFixOptions::first_plan_dive: one node per
// stage, the stage roundings on, group-order branching.
RelaxAndFixOptions DiveOptions(RelaxAndFixOptions options);

// The dive of RelaxAndFixOptions::rounding_dive from the root relaxation's point root_x:
// one QP (or one per proposal, up to the first completed) per configuration, solved with
// solver under the sooner of options.stage's deadline and options.time_limit_s (the dive's
// share), with options.stage's feasibility tolerance. Anytime as RelaxAndFix: when the
// share passes after a stage was completed, the configurations left are rounded along the
// plan from the latest stage's point under options.stage's deadline extended by
// options.completion_overrun_s (completed_by_rounding; those QPs are counted in relaxations
// too), skipping the roundings whose stage QP already failed. A stage is cut short only
// when one of its QPs ends unsolved after the share has passed: when its roundings all
// fail on their own (infeasible, or failed within the share), the dive ends without a plan
// and without a completion, which would solve the same roundings again. No plan either
// when the share passes before a stage is completed, or the completion's deadline passes.
RelaxAndFixResult RoundingDive(const MiqpFormulation& formulation, RelaxationSolver& solver,
                               const Eigen::VectorXd& root_x, const RelaxAndFixOptions& options);

// Each stage's search runs with the given workers (SolveBranchAndBound); none of them may
// be in use elsewhere meanwhile.
RelaxAndFixResult RelaxAndFix(const MiqpFormulation& formulation, const std::vector<RelaxationSolver*>& solvers,
                              const RelaxAndFixOptions& options);

// With two or more solvers: two single-worker runs side by side, the second with its
// stage QPs at the solver's own accuracy, and the better plan (stages, nodes and
// relaxations are summed; completed_by_rounding is the better plan's). A stage's choice
// can turn on differences within its QPs' tolerance, so one path can end far from the
// other (docs/measurements.md); two paths make such a turn matter less, and the first
// path is the one-worker run, so two workers plan no worse than one. With one solver: RelaxAndFix.
RelaxAndFixResult RelaxAndFixTwoPaths(const MiqpFormulation& formulation,
                                      const std::vector<RelaxationSolver*>& solvers,
                                      const RelaxAndFixOptions& options);

}  // namespace mfp
