#include "planner/qp/internal/dual_active_set_relaxation_solver.h"

#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

namespace mfp {
namespace {

// TEMPORARY TRACE.
struct HandTrace {
  long no_token = 0, no_children = 0, dual_done = 0, dual_to_ipm = 0, ipm_steps_after = 0, dual_steps_wasted = 0;
  ~HandTrace() {
    if (!std::getenv("MFP_DUAL_TRACE")) return;
    std::fprintf(stderr, "HANDTRACE no_token %ld no_children %ld dual_done %ld dual_to_ipm %ld (wasted steps %ld, ipm its %ld)\n",
                 no_token, no_children, dual_done, dual_to_ipm, dual_steps_wasted, ipm_steps_after);
  }
};
HandTrace& Hand() {
  static HandTrace t;
  return t;
}

bool SomeIntegerFree(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  for (int j = 0; j < problem.num_variables(); ++j) {
    if (problem.is_integer[j] && lower(j) < upper(j)) return true;
  }
  return false;
}

class DualActiveSetRelaxationSolver final : public RelaxationSolver {
 public:
  DualActiveSetRelaxationSolver(std::unique_ptr<RelaxationSolver> interior, const DualActiveSetOptions& options)
      : qp_(TraceOptions(options)), interior_(std::move(interior)) {}
  // TEMPORARY: experiment switches.
  static DualActiveSetOptions TraceOptions(DualActiveSetOptions o) {
    if (const char* v = std::getenv("MFP_DUAL_PROX")) o.proximal_centre = std::atoi(v) != 0;
    if (const char* v = std::getenv("MFP_DUAL_ENTER")) o.enter_moved_bounds = std::atoi(v) != 0;
    if (const char* v = std::getenv("MFP_DUAL_REG")) o.regularisation = std::atof(v);
    if (const char* v = std::getenv("MFP_DUAL_MAXVAR")) o.max_variables = std::atoi(v);
    if (const char* v = std::getenv("MFP_DUAL_BUDGET")) o.max_warm_steps_per_variable = std::atof(v);
    if (const char* v = std::getenv("MFP_DUAL_SNAPS")) o.snapshots = std::atoi(v);
    return o;
  }

  // The warm start point is not used: the dual method starts from the token's active set.
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    const Eigen::VectorXd& lower = request.LowerOr(problem);
    const Eigen::VectorXd& upper = request.UpperOr(problem);
    // A QP whose integers are all fixed (a rounding, a leaf) has no children: it neither
    // takes nor gives a token.
    const bool has_children = SomeIntegerFree(problem, lower, upper);
    int dual_steps = 0;
    if (!request.warm_token) ++Hand().no_token;
    else if (!has_children) ++Hand().no_children;
    if (request.warm_token && has_children) {
      RelaxationResult dual = qp_.SolveFrom(problem, lower, upper, request.cutoff, request.deadline, *request.warm_token,
                                            request.WarmStart());
      if (dual.status == RelaxationStatus::kSolved || dual.status == RelaxationStatus::kCutoff ||
          dual.status == RelaxationStatus::kInfeasible || request.deadline.Expired()) {
        ++Hand().dual_done;
        return dual;
      }
      dual_steps = dual.iterations;
      ++Hand().dual_to_ipm;
      Hand().dual_steps_wasted += dual_steps;
    }
    RelaxationResult result = interior_->Solve(problem, request);
    if (dual_steps) Hand().ipm_steps_after += result.iterations;
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
