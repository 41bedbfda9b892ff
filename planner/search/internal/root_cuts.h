#pragma once
// The root cut loop (BranchAndBoundOptions::root_cut_rounds): solve the root relaxation,
// separate the families of options.root_cut_families against its point (c-MIR and group
// bound cuts, mir_cuts.h; implied-bound and clique cuts from probing the binaries,
// implied_cuts.h), add the most efficacious as rows, re-solve, for a few rounds. The cuts
// are valid for every integer-feasible point of the problem (they are derived from its
// rows, its bounds after propagation and probing, and integrality), so the search may run
// on the problem with the cuts as if it were the original: same feasible plans, same
// optimum, a higher root bound. Given a plan's objective, the loop first rules out the
// integer values that the first relaxation's reduced costs prove cannot beat it; the
// cuts then hold for every plan at least as good as that one.
#include <Eigen/Core>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

struct RootCutLoopResult {
  Miqp problem;  // the input with the kept cuts appended as rows "cut_K" (<= side only)
  int cuts = 0;  // rows appended
  int cuts_by_family[4] = {0, 0, 0, 0};  // rows appended of each RootCutFamily, in its bit order
  int reduced_cost_fixings = 0;  // integer bounds tightened against the plan given
  int probing_fixings = 0;       // binaries fixed because probing proved the other value infeasible
  int rounds = 0;  // separation rounds that added cuts
  int relaxations = 0;
  int fallbacks = 0;             // of them, solved by the solver's fallback (RelaxationResult::fallbacks)
  double fallback_time_s = 0.0;  // and those solves' wall time
  double bound_before = -kInfinity;  // the first relaxation's objective (-inf when unsolved)
  double bound_after = -kInfinity;   // the last solved relaxation's objective
};

// Runs the loop under options' root_cut_* settings and the deadline; an infeasible or
// unsolved root relaxation ends it with the cuts found so far. incumbent_objective: a
// plan's objective (infinity: none). With a plan, the returned problem's variable bounds
// are the loop's (after propagation, probing and reduced-cost fixing): they keep every
// plan better than the given one, so its search must hold that plan.
RootCutLoopResult RunRootCutLoop(const Miqp& problem, RelaxationSolver& solver, const BranchAndBoundOptions& options,
                                 const Deadline& deadline, double incumbent_objective = kInfinity);

}  // namespace mfp
