#include "planner/qp/relaxation_solver_factory.h"

#include "base/check.h"
#include "planner/qp/internal/dual_active_set_relaxation_solver.h"
#include "planner/qp/internal/fallback_relaxation_solver.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/qp/internal/ipopt_relaxation_solver.h"

namespace mfp {
namespace {

std::unique_ptr<RelaxationSolver> MakeInteriorPointWithIpoptFallback() {
  return MakeFallbackRelaxationSolver(MakeInteriorPointRelaxationSolver(), MakeIpoptRelaxationSolver());
}

}  // namespace

RelaxationBackend ParseRelaxationBackend(const std::string& name) {
  if (name == "ipm") return RelaxationBackend::kInteriorPointWithIpoptFallback;
  if (name == "ipopt") return RelaxationBackend::kIpopt;
  if (name == "dualqp") return RelaxationBackend::kDualActiveSetWithFallbacks;
  throw InputError("relaxation solver '" + name + "' is not one of ipm, ipopt, dualqp");
}

std::string ToString(RelaxationBackend backend) {
  if (backend == RelaxationBackend::kIpopt) return "ipopt";
  return backend == RelaxationBackend::kDualActiveSetWithFallbacks ? "dualqp" : "ipm";
}

std::unique_ptr<RelaxationSolver> MakeRelaxationSolver(RelaxationBackend backend) {
  if (backend == RelaxationBackend::kIpopt) return MakeIpoptRelaxationSolver();
  if (backend == RelaxationBackend::kInteriorPointWithIpoptFallback) return MakeInteriorPointWithIpoptFallback();
  return MakeDualActiveSetRelaxationSolver(MakeInteriorPointWithIpoptFallback());
}

std::vector<RelaxationSolver*> RelaxationSolverSet::workers() const {
  std::vector<RelaxationSolver*> out;
  for (const auto& s : owned) out.push_back(s.get());
  return out;
}

RelaxationSolverSet MakeRelaxationSolvers(RelaxationBackend backend, int count) {
  MFP_CHECK(count >= 1);
  RelaxationSolverSet set;
  for (int k = 0; k < count; ++k) set.owned.push_back(MakeRelaxationSolver(backend));
  return set;
}

RelaxationSolverSet MakeRelaxationSolvers(const RelaxationSolverOptions& options) {
  return MakeRelaxationSolvers(options.backend, options.threads);
}

}  // namespace mfp
