#pragma once
// The root cut loop (BranchAndBoundOptions::root_cut_rounds): solve the root relaxation,
// separate group bound cuts and c-MIR cuts (mir_cuts.h) against its point, add the most
// efficacious as rows, re-solve, for a few rounds. The cuts are valid for every integer-feasible point of the
// problem (they are derived from its rows, its bounds after propagation and
// integrality), so the search may run on the problem with the cuts as if it were the
// original: same feasible plans, same optimum, a higher root bound.
#include <Eigen/Core>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

struct RootCutLoopResult {
  Miqp problem;  // the input with the kept cuts appended as rows "cut_K" (<= side only)
  int cuts = 0;  // rows appended
  int rounds = 0;  // separation rounds that added cuts
  int relaxations = 0;
  double bound_before = -kInfinity;  // the first relaxation's objective (-inf when unsolved)
  double bound_after = -kInfinity;   // the last solved relaxation's objective
};

// Runs the loop under options' root_cut_* settings and the deadline; an infeasible or
// unsolved root relaxation ends it with the cuts found so far.
RootCutLoopResult RunRootCutLoop(const Miqp& problem, RelaxationSolver& solver, const BranchAndBoundOptions& options,
                                 const Deadline& deadline);

}  // namespace mfp
