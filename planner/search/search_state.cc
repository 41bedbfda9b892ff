#include "planner/search/internal/search_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "planner/qp/fixed_integer_qp.h"

namespace mfp {

SearchState::SearchState(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers,
                         const BranchAndBoundOptions& options)
    : p_(problem),
      solvers_(solvers),
      opt_(options),
      start_(Clock::now()),
      deadline_(options.deadline.Within(options.time_limit_s)),
      hard_deadline_(options.time_limit_needs_incumbent ? options.deadline : deadline_),
      queue_(options.node_selection, options.plunge_fraction),
      lagging_(options.recertify_leaves) {}

double SearchState::StallTimeLeftSeconds() const {
  if (!(opt_.stall_time_fraction > 0.0) || !HasIncumbent()) return std::numeric_limits<double>::infinity();
  return opt_.stall_time_fraction * opt_.time_limit_s -
         std::chrono::duration<double>(Clock::now() - last_improvement_).count();
}

bool SearchState::Stalled() const { return StallTimeLeftSeconds() < 0.0; }

bool SearchState::IsLong() const {
  return result_.nodes >= opt_.long_search_min_nodes && TimeHoldsNodes(opt_.long_search_nodes_left);
}

bool SearchState::TimeHoldsNodes(double nodes) const {
  const double left_s = std::min(Active().RemainingSeconds(), StallTimeLeftSeconds());
  const double per_node_s = Elapsed() / std::max(1, result_.nodes);
  return left_s >= nodes * per_node_s;
}

double SearchState::GapTolerance() const {
  return std::max(opt_.absolute_gap, opt_.relative_gap * std::max(1.0, std::abs(result_.objective)));
}

void SearchState::OfferIncumbent(Eigen::VectorXd x, bool report) {
  const std::optional<double> objective = FeasibleObjective(p_, &x, opt_.feasibility_tolerance);
  if (!objective) return;
  if (Restricted() && !Within(x, restricted_lower_, restricted_upper_)) return;
  if (!HasIncumbent() || *objective < result_.objective) {
    result_.x = std::move(x);
    result_.objective = *objective;
    last_improvement_ = Clock::now();
    last_improvement_node_ = result_.nodes;
    if (report && opt_.on_incumbent) ReportProgress();
  }
}

void SearchState::Restrict(Eigen::VectorXd lower, Eigen::VectorXd upper) {
  restricted_lower_ = std::move(lower);
  restricted_upper_ = std::move(upper);
  result_.restricted = true;
}

bool SearchState::Within(const Eigen::VectorXd& x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) const {
  const double tol = opt_.feasibility_tolerance;
  return !((x.array() < lower.array() - tol).any() || (x.array() > upper.array() + tol).any());
}

RelaxationRequest SearchState::Request(Eigen::VectorXd lower, Eigen::VectorXd upper, const Eigen::VectorXd* warm,
                                       double cutoff) const {
  RelaxationRequest request;
  request.lower = std::move(lower);
  request.upper = std::move(upper);
  if (warm != nullptr) request.warm_start = *warm;
  request.deadline = Active();
  if (opt_.early_cutoff) request.cutoff = cutoff;
  request.relative_tolerance = opt_.relaxation_tolerance;
  request.polish_tolerance = opt_.relaxation_polish;
  return request;
}

double SearchState::UnexploredBound() const {
  return std::min({in_flight_bound_, unresolved_bound_, gap_pruned_bound_, queue_.LeastFloor()});
}

double RelativeGap(double objective, double bound) { return (objective - bound) / std::max(1.0, std::abs(objective)); }

void SearchState::ReportProgress() const {
  BranchAndBoundResult progress;
  progress.status = SolveStatus::kFeasible;
  progress.objective = result_.objective;
  progress.bound = BoundNow();
  progress.gap = RelativeGap(progress.objective, progress.bound);
  progress.nodes = result_.nodes;
  progress.relaxations = result_.relaxations;
  progress.strong_branching_solves = result_.strong_branching_solves;
  progress.propagation_prunes = result_.propagation_prunes;
  progress.solve_time_s = Elapsed();
  opt_.on_incumbent(progress);
}

}  // namespace mfp
