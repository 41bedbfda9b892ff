#pragma once
// Making the branch-and-bound's relaxation solvers: which backend, how many workers.
#include <memory>
#include <string>
#include <vector>

#include "planner/qp/relaxation_solver.h"

namespace mfp {

enum class RelaxationBackend {
  // mfp's sparse interior-point method (interior_point_qp.h); a node it cannot resolve
  // within its iteration limit is handed to Ipopt. The default: far faster per node
  // (docs/measurements.md).
  kInteriorPointWithIpoptFallback,
  kIpopt,  // Ipopt alone
  // mfp's dense dual active-set method warm-started from the worker's nearest recent node
  // (dual_active_set_qp.h) for node relaxations; a node it does not finish (too many
  // variables, found infeasible, step cap) goes to the interior point, then Ipopt. QPs
  // with every integer fixed (the heuristics') go to the interior point directly.
  kDualActiveSetWithFallbacks,
};

// "ipm", "ipopt" or "dualqp"; throws InputError naming the allowed values otherwise.
RelaxationBackend ParseRelaxationBackend(const std::string& name);
std::string ToString(RelaxationBackend backend);

// The solvers a plan uses, set by the `planner:` keys `relaxation_solver` and `threads`
// (io/planner_options_yaml.cc) and mfp-plan's --relaxation-solver, --threads.
struct RelaxationSolverOptions {
  RelaxationBackend backend = RelaxationBackend::kInteriorPointWithIpoptFallback;
  // Branch-and-bound workers, each with a relaxation solver of its own: node relaxations
  // are solved this many at a time.
  int threads = 1;
};

std::unique_ptr<RelaxationSolver> MakeRelaxationSolver(RelaxationBackend backend);

// One solver per branch-and-bound worker; workers() is what PlanFootsteps takes.
struct RelaxationSolverSet {
  std::vector<std::unique_ptr<RelaxationSolver>> owned;
  std::vector<RelaxationSolver*> workers() const;
};
RelaxationSolverSet MakeRelaxationSolvers(RelaxationBackend backend, int count);
// options.threads solvers of options.backend.
RelaxationSolverSet MakeRelaxationSolvers(const RelaxationSolverOptions& options);

}  // namespace mfp
