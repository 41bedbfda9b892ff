#include "planner/qp/internal/dual_active_set_relaxation_solver.h"

#include <utility>
#include <vector>

namespace mfp {
namespace {

bool SomeIntegerFree(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  for (int j = 0; j < problem.num_variables(); ++j) {
    if (problem.is_integer[j] && lower(j) < upper(j)) return true;
  }
  return false;
}

class DualActiveSetRelaxationSolver final : public RelaxationSolver {
 public:
  DualActiveSetRelaxationSolver(std::unique_ptr<RelaxationSolver> interior, const DualActiveSetOptions& options)
      : qp_(options), interior_(std::move(interior)) {}

  // The warm start point is not used: the dual method starts from the token's active set.
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    const Eigen::VectorXd& lower = request.LowerOr(problem);
    const Eigen::VectorXd& upper = request.UpperOr(problem);
    // A QP whose integers are all fixed (a rounding, a leaf) has no children: it neither
    // takes nor gives a token.
    const bool has_children = SomeIntegerFree(problem, lower, upper);
    int dual_steps = 0;
    if (request.warm_token && has_children) {
      RelaxationResult dual = qp_.SolveFrom(problem, lower, upper, request.cutoff, request.deadline, *request.warm_token,
                                            request.WarmStart());
      if (dual.status == RelaxationStatus::kSolved || dual.status == RelaxationStatus::kCutoff ||
          dual.status == RelaxationStatus::kInfeasible || request.deadline.Expired()) {
        return dual;
      }
      dual_steps = dual.iterations;
    }
    RelaxationResult result = interior_->Solve(problem, request);
    result.iterations += dual_steps;
    if (result.status == RelaxationStatus::kSolved && has_children) {
      result.warm_token =
          std::make_shared<const std::vector<int>>(DualActiveSetQp::ActiveSetAt(problem, lower, upper, result));
    }
    return result;
  }

  std::string Name() const override { return "dualqp+" + interior_->Name(); }

 private:
  DualActiveSetQp qp_;
  std::unique_ptr<RelaxationSolver> interior_;
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeDualActiveSetRelaxationSolver(std::unique_ptr<RelaxationSolver> interior,
                                                                    const DualActiveSetOptions& options) {
  return std::make_unique<DualActiveSetRelaxationSolver>(std::move(interior), options);
}

}  // namespace mfp
