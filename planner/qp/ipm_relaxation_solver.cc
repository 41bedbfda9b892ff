#include "planner/qp/ipm_relaxation_solver.h"

#include <algorithm>

#include "planner/base/check.h"
#include "planner/qp/fixed_variable_reduction.h"

namespace mfp {
namespace {

class InteriorPointRelaxationSolver final : public RelaxationSolver {
 public:
  explicit InteriorPointRelaxationSolver(const InteriorPointOptions& options) : options_(options) {}

  RelaxationResult Solve(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                         const Eigen::VectorXd* warm_start) override {
    RelaxationResult result;
    ReducedQp reduced;
    InteriorPointOptions options = options_;
    options.cutoff = cutoff_;
    options.deadline = deadline_;
    options.tolerance = std::max(options.tolerance, tolerance_);
    cutoff_ = kInfinity;  // the next solve only
    tolerance_ = 0.0;
    if (ReduceOrSettle(problem, lower, upper, options.infeasible_violation, &reduced, &result)) return result;
    Eigen::VectorXd start;
    if (warm_start != nullptr) start = reduced.Restrict(*warm_start);
    const RelaxationResult r = SolveQpInteriorPoint(reduced.problem, reduced.lower, reduced.upper,
                                                    warm_start != nullptr ? &start : nullptr, options);
    result.status = r.status;
    result.iterations = r.iterations;
    result.x = reduced.Expand(r.x);
    // A cutoff's objective is its floor (the reduced problem's constant holds the fixed
    // variables' part), not the value at its unfinished point.
    result.objective = r.status == RelaxationStatus::kCutoff ? r.objective : problem.Objective(result.x);
    if (r.lower_cost_rate.size() > 0) {
      // The reduced problem's objective differs from the original's by rounding only
      // (its constant holds the fixed part); rates of fixed variables are 0.
      result.cost_floor = std::min(result.objective, r.cost_floor - 1e-9 * (1.0 + std::abs(r.cost_floor)));
      result.lower_cost_rate = Eigen::VectorXd::Zero(problem.num_variables());
      result.upper_cost_rate = Eigen::VectorXd::Zero(problem.num_variables());
      for (size_t k = 0; k < reduced.free_index.size(); ++k) {
        result.lower_cost_rate(reduced.free_index[k]) = r.lower_cost_rate(static_cast<Eigen::Index>(k));
        result.upper_cost_rate(reduced.free_index[k]) = r.upper_cost_rate(static_cast<Eigen::Index>(k));
      }
    }
    return result;
  }

  void SetTimeLimit(double) override {}  // SetDeadline holds the time
  void SetDeadline(const Deadline& deadline) override { deadline_ = deadline; }
  void SetCutoff(double objective) override { cutoff_ = objective; }
  void SetRelativeTolerance(double tolerance) override { tolerance_ = tolerance; }
  std::string Name() const override { return "ipm"; }

 private:
  InteriorPointOptions options_;
  double cutoff_ = kInfinity;
  double tolerance_ = 0.0;  // 0: options_.tolerance
  Deadline deadline_;
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeInteriorPointRelaxationSolver(const InteriorPointOptions& options) {
  return std::make_unique<InteriorPointRelaxationSolver>(options);
}

}  // namespace mfp
