#include "planner/qp/internal/dual_active_set_relaxation_solver.h"

namespace mfp {
namespace {

class DualActiveSetRelaxationSolver final : public RelaxationSolver {
 public:
  explicit DualActiveSetRelaxationSolver(const DualActiveSetOptions& options) : qp_(options) {}

  // The warm start point is not used: the solver restarts from its own last active set.
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    return qp_.Solve(problem, request.LowerOr(problem), request.UpperOr(problem), request.cutoff, request.deadline);
  }

  std::string Name() const override { return "dualqp"; }

 private:
  DualActiveSetQp qp_;
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeDualActiveSetRelaxationSolver(const DualActiveSetOptions& options) {
  return std::make_unique<DualActiveSetRelaxationSolver>(options);
}

}  // namespace mfp
