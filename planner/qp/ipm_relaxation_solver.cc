#include "planner/qp/internal/ipm_relaxation_solver.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "base/check.h"
#include "planner/qp/internal/fixed_variable_reduction.h"

namespace mfp {
namespace {

// RelaxationRequest::certify_floor's second method (FloorCertificationOptions): the dual
// active-set method from the active set of the interior point's solved answer r of the
// reduced QP, stopping once its floor reaches cutoff. Its solved answer (an optimum exact
// to its regularisation, with its floor) replaces r when it certifies more; a cutoff's
// floor (its objective) raises r's bound_floor, never above r's objective.
void CertifyByActiveSet(const ReducedQp& reduced, double cutoff, const Deadline& deadline,
                        const FloorCertificationOptions& certification, RelaxationResult* r) {
  const std::vector<int> start = DualActiveSetQp::ActiveSetAt(reduced.problem, reduced.lower, reduced.upper, *r);
  DualActiveSetQp exact(certification.active_set);
  RelaxationResult solved = exact.SolveFrom(reduced.problem, reduced.lower, reduced.upper, cutoff, deadline, start);
  solved.iterations += r->iterations;
  solved.polish_attempts = r->polish_attempts;
  if (solved.status == RelaxationStatus::kSolved && solved.CertifiedFloor() > r->CertifiedFloor()) {
    *r = std::move(solved);
    return;
  }
  r->iterations = solved.iterations;
  if (solved.status == RelaxationStatus::kCutoff) {
    r->bound_floor = std::max(r->bound_floor, std::min(r->objective, solved.objective));
  }
}

class InteriorPointRelaxationSolver final : public RelaxationSolver {
 public:
  InteriorPointRelaxationSolver(const InteriorPointOptions& options, const FloorCertificationOptions& certification)
      : options_(options), certification_(certification) {}

  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    RelaxationResult result;
    ReducedQp reduced;
    InteriorPointOptions options = options_;
    options.cutoff = request.cutoff;
    options.deadline = request.deadline;
    options.tolerance = std::max(options.tolerance, request.relative_tolerance);
    if (request.polish_tolerance > 0.0) options.polish_tolerance = request.polish_tolerance;
    // Re-certification tries the crossover once, at convergence (a tolerance no looser
    // than the solve's own).
    if (request.certify_floor && !(options.polish_tolerance > 0.0)) options.polish_tolerance = options.tolerance;
    const Eigen::VectorXd& lower = request.LowerOr(problem);
    const Eigen::VectorXd& upper = request.UpperOr(problem);
    const Eigen::VectorXd* warm_start = request.WarmStart();
    if (ReduceOrSettle(problem, lower, upper, options.infeasible_violation, &reduced, &result)) return result;
    Eigen::VectorXd start;
    if (warm_start != nullptr) start = reduced.Restrict(*warm_start);
    RelaxationResult r = SolveQpInteriorPoint(reduced.problem, reduced.lower, reduced.upper,
                                              warm_start != nullptr ? &start : nullptr, options);
    if (request.certify_floor && r.status == RelaxationStatus::kSolved && r.polished == 0) {
      CertifyByActiveSet(reduced, request.cutoff, request.deadline, certification_, &r);
    }
    result.status = r.status;
    result.over_work_budget = r.over_work_budget;
    result.iterations = r.iterations;
    result.polish_attempts = r.polish_attempts;
    result.polished = r.polished;
    result.x = reduced.Expand(r.x);
    // A cutoff's objective is its floor (the reduced problem's constant holds the fixed
    // variables' part), not the value at its unfinished point.
    result.objective = r.status == RelaxationStatus::kCutoff ? r.objective : problem.Objective(result.x);
    if (r.lower_cost_rate.size() > 0) {
      // The reduced problem's objective differs from the original's by rounding only
      // (its constant holds the fixed part); rates of fixed variables are 0.
      result.cost_floor = std::min(result.objective, r.cost_floor - 1e-9 * (1.0 + std::abs(r.cost_floor)));
      result.bound_floor =
          std::max(result.cost_floor, std::min(result.objective, r.bound_floor - 1e-9 * (1.0 + std::abs(r.bound_floor))));
      result.lower_cost_rate = Eigen::VectorXd::Zero(problem.num_variables());
      result.upper_cost_rate = Eigen::VectorXd::Zero(problem.num_variables());
      for (size_t k = 0; k < reduced.free_index.size(); ++k) {
        result.lower_cost_rate(reduced.free_index[k]) = r.lower_cost_rate(static_cast<Eigen::Index>(k));
        result.upper_cost_rate(reduced.free_index[k]) = r.upper_cost_rate(static_cast<Eigen::Index>(k));
      }
      if (r.row_lower_rate.size() > 0) {  // rows the reduction dropped are inactive: rate 0
        result.row_lower_rate = Eigen::VectorXd::Zero(problem.num_rows());
        result.row_upper_rate = Eigen::VectorXd::Zero(problem.num_rows());
        for (size_t k = 0; k < reduced.row_index.size(); ++k) {
          result.row_lower_rate(reduced.row_index[k]) = r.row_lower_rate(static_cast<Eigen::Index>(k));
          result.row_upper_rate(reduced.row_index[k]) = r.row_upper_rate(static_cast<Eigen::Index>(k));
        }
      }
    }
    return result;
  }

  std::string Name() const override { return "ipm"; }

 private:
  InteriorPointOptions options_;
  FloorCertificationOptions certification_;
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeInteriorPointRelaxationSolver(const InteriorPointOptions& options,
                                                                   const FloorCertificationOptions& certification) {
  return std::make_unique<InteriorPointRelaxationSolver>(options, certification);
}

}  // namespace mfp
