#pragma once
// Choosing the relaxation backend by name (config, flags).
#include <memory>
#include <string>
#include <vector>

#include "planner/qp/relaxation_solver.h"

namespace mfp {

enum class RelaxationBackend {
  // mfp's sparse interior-point method (interior_point_qp.h); a node it cannot resolve
  // within its iteration limit is handed to Ipopt. The default: ~20x faster per node.
  kInteriorPointWithIpoptFallback,
  kIpopt,  // Ipopt alone
};

// "ipm" or "ipopt"; throws InputError naming the allowed values otherwise.
RelaxationBackend ParseRelaxationBackend(const std::string& name);
std::string ToString(RelaxationBackend backend);

std::unique_ptr<RelaxationSolver> MakeRelaxationSolver(RelaxationBackend backend);

// One solver per branch-and-bound worker; workers() is what PlanFootsteps takes.
struct RelaxationSolverSet {
  std::vector<std::unique_ptr<RelaxationSolver>> owned;
  std::vector<RelaxationSolver*> workers() const;
};
RelaxationSolverSet MakeRelaxationSolvers(RelaxationBackend backend, int count);

}  // namespace mfp
