#include "planner/qp/relaxation_solver_factory.h"

#include "base/check.h"
#include "planner/qp/internal/dual_active_set_relaxation_solver.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/qp/internal/ipopt_relaxation_solver.h"

namespace mfp {
namespace {

// Asks the fallback whenever the primary solver ends without an answer.
class FallbackRelaxationSolver final : public RelaxationSolver {
 public:
  FallbackRelaxationSolver(std::unique_ptr<RelaxationSolver> primary, std::unique_ptr<RelaxationSolver> fallback)
      : primary_(std::move(primary)), fallback_(std::move(fallback)) {}

  // The fallback solves to the end: it gets the request without its cutoff.
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    RelaxationResult result = primary_->Solve(problem, request);
    if (result.status == RelaxationStatus::kSolved || result.status == RelaxationStatus::kInfeasible ||
        result.status == RelaxationStatus::kCutoff || request.deadline.Expired() || result.over_work_budget) {
      return result;
    }
    RelaxationRequest to_the_end = request;
    to_the_end.cutoff = kInfinity;
    to_the_end.relative_tolerance = 0.0;
    return fallback_->Solve(problem, to_the_end);
  }

  std::string Name() const override { return primary_->Name() + "+" + fallback_->Name(); }

 private:
  std::unique_ptr<RelaxationSolver> primary_;
  std::unique_ptr<RelaxationSolver> fallback_;
};

std::unique_ptr<RelaxationSolver> MakeInteriorPointWithIpoptFallback() {
  return std::make_unique<FallbackRelaxationSolver>(MakeInteriorPointRelaxationSolver(), MakeIpoptRelaxationSolver());
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
