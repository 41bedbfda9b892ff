#include "planner/ipm_relaxation_solver.h"

#include "planner/check.h"
#include "planner/fixed_variable_reduction.h"

namespace mfp {
namespace {

class InteriorPointRelaxationSolver final : public RelaxationSolver {
 public:
  explicit InteriorPointRelaxationSolver(const InteriorPointOptions& options) : options_(options) {}

  RelaxationResult Solve(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                         const Eigen::VectorXd* warm_start) override {
    RelaxationResult result;
    ReducedQp reduced;
    if (ReduceOrSettle(problem, lower, upper, options_.infeasible_violation, &reduced, &result)) return result;
    Eigen::VectorXd start;
    if (warm_start != nullptr) start = reduced.Restrict(*warm_start);
    const RelaxationResult r = SolveQpInteriorPoint(reduced.problem, reduced.lower, reduced.upper,
                                                    warm_start != nullptr ? &start : nullptr, options_);
    result.status = r.status;
    result.iterations = r.iterations;
    result.x = reduced.Expand(r.x);
    result.objective = problem.Objective(result.x);
    return result;
  }

  void SetTimeLimit(double) override {}  // one solve takes milliseconds
  std::string Name() const override { return "ipm"; }

 private:
  InteriorPointOptions options_;
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeInteriorPointRelaxationSolver(const InteriorPointOptions& options) {
  return std::make_unique<InteriorPointRelaxationSolver>(options);
}

}  // namespace mfp
