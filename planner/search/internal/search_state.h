#pragma once
// What the parts of a branch-and-bound share: the problem, the workers' relaxation
// solvers, the deadlines, the open nodes, the incumbent with the bound and counters of
// the result so far, and the bookkeeping of the subtrees settled without a bound of
// their own. The search loop (branch_and_bound.cc), the branching rules, the heuristics
// and the reduced-cost fixing all act on it.
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/lagging_floors.h"
#include "planner/search/internal/node_queue.h"

namespace mfp {

class SearchState {
 public:
  using Clock = std::chrono::steady_clock;

  SearchState(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers,
              const BranchAndBoundOptions& options);

  const Miqp& problem() const { return p_; }
  const BranchAndBoundOptions& options() const { return opt_; }
  RelaxationSolver& solver(int worker) const { return *solvers_[worker]; }
  int workers() const { return static_cast<int>(solvers_.size()); }
  NodeQueue& queue() { return queue_; }
  const NodeQueue& queue() const { return queue_; }
  BranchAndBoundResult& result() { return result_; }
  const BranchAndBoundResult& result() const { return result_; }

  // The deadline in force: the time limit's, or before the first incumbent under
  // time_limit_needs_incumbent the caller's alone.
  const Deadline& Active() const { return !HasIncumbent() ? hard_deadline_ : deadline_; }
  // The deadline of the QPs that complete a rounding: Active(), extended by
  // options.first_plan_overrun_s while the search holds no plan.
  Deadline RoundingDeadline() const {
    return HasIncumbent() ? Active() : Active().ExtendedBy(opt_.first_plan_overrun_s);
  }
  // BranchAndBoundOptions::stall_time_fraction: the time left before the search counts as
  // stalled (infinite without a stall limit or before its first plan) [s], and whether it is.
  double StallTimeLeftSeconds() const;
  bool Stalled() const;
  // BranchAndBoundOptions::long_search_min_nodes and long_search_nodes_left.
  bool IsLong() const;
  // True when the time left (to the deadline in force, and to the stall limit) would hold
  // `nodes` more nodes at the search's mean time per node so far (its elapsed time over
  // its processed nodes, at least one).
  bool TimeHoldsNodes(double nodes) const;
  // True when `lever` (a LongSearchLever) may run now: it is not kept to long searches,
  // or the search is long.
  bool LeverPays(int lever) const { return (opt_.long_search_only & lever) == 0 || IsLong(); }
  double Elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  bool HasIncumbent() const { return result_.x.size() > 0; }
  // The nodes processed since the incumbent last improved (all of them before the first).
  int NodesSinceImprovement() const { return result_.nodes - last_improvement_node_; }
  // True when a subtree with this bound may still beat the incumbent by more than the gap.
  bool Improves(double bound) const { return bound < result_.objective - GapTolerance(); }
  // How much better than the incumbent a subtree must be able to get to be explored.
  double GapTolerance() const;
  // x with its integers rounded becomes the incumbent when it meets the rows and bounds
  // (and the restriction, once set) and beats the incumbent; then, with `report`,
  // options.on_incumbent is told.
  void OfferIncumbent(Eigen::VectorXd x, bool report = true);
  // Re-certification's restriction (BranchAndBoundOptions::recertify_within): from now on
  // no point outside lower/upper (within the feasibility tolerance) becomes the incumbent.
  void Restrict(Eigen::VectorXd lower, Eigen::VectorXd upper);
  bool Restricted() const { return restricted_lower_.size() > 0; }
  // BranchAndBoundOptions::recertify_within is asked once per search: true the first time.
  bool FirstRestrictionAsk() { return !std::exchange(restriction_asked_, true); }
  // x lies within lower/upper, within the feasibility tolerance.
  bool Within(const Eigen::VectorXd& x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) const;

  // The request for one relaxation within the node bounds lower/upper, under the
  // deadline in force. cutoff: see BranchAndBoundOptions::early_cutoff.
  RelaxationRequest Request(Eigen::VectorXd lower, Eigen::VectorXd upper, const Eigen::VectorXd* warm,
                            double cutoff = kInfinity) const;
  RelaxationResult SolveWith(RelaxationSolver& solver, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                             const Eigen::VectorXd* warm, double cutoff = kInfinity) const {
    return solver.Solve(p_, Request(lower, upper, warm, cutoff));
  }

  // A subtree dropped because it cannot beat the incumbent by more than the gap still
  // bounds the optimum: the reported bound must not rise above it.
  void NoteGapPrune(double bound) {
    gap_pruned_bound_ = std::min(gap_pruned_bound_, bound);
    lagging_.NoteFloor(bound);
  }
  // The same with the subtree's box (SettledSubtree), which the search may keep to
  // certify its floor again (BranchAndBoundOptions::recertify_leaves).
  void NoteGapPrune(SettledSubtree subtree) {
    gap_pruned_bound_ = std::min(gap_pruned_bound_, subtree.floor);
    lagging_.Note(std::move(subtree), ProofFloor());
  }
  // Whether a subtree settled at `floor` now would be kept (its box is worth building).
  bool KeepsForRecertification(double floor) const { return lagging_.Keeps(floor, ProofFloor()); }
  // The floor every settled subtree must reach for the incumbent to be proven within
  // the gap asked (-infinity without an incumbent).
  double ProofFloor() const { return HasIncumbent() ? result_.objective - GapTolerance() : -kInfinity; }
  LaggingFloors& lagging() { return lagging_; }
  // After re-certification: the least floor of the settled subtrees (LaggingFloors::Least).
  void RaiseGapPrunedBound() { gap_pruned_bound_ = std::max(gap_pruned_bound_, lagging_.Least()); }
  // A subtree dropped because its relaxation could not be solved: optimality is unproven.
  void NoteUnresolved(double bound) { unresolved_bound_ = std::min(unresolved_bound_, bound); }
  bool HasUnresolved() const { return unresolved_bound_ < kInfinity; }
  double gap_pruned_bound() const { return gap_pruned_bound_; }
  // The nodes of a round being evaluated have left the queue: their least parent bound
  // (infinity between rounds, once every node of the round is settled or back in the queue).
  void SetInFlightBound(double bound) { in_flight_bound_ = bound; }
  double in_flight_bound() const { return in_flight_bound_; }

  // The least bound of everything not yet settled: open nodes, the round in flight,
  // subtrees that could not be bounded and subtrees pruned by the gap tolerance.
  double UnexploredBound() const;
  // The search's bound at this moment: the settled bound raised to what its open and
  // in-flight nodes allow, never above the incumbent (progress reports, RINS's gap gate).
  double BoundNow() const { return std::min(result_.objective, std::max(result_.bound, UnexploredBound())); }

 private:
  void ReportProgress() const;

  const Miqp& p_;
  const std::vector<RelaxationSolver*>& solvers_;  // one per worker
  const BranchAndBoundOptions& opt_;
  const Clock::time_point start_;
  Clock::time_point last_improvement_;  // when the incumbent last improved
  int last_improvement_node_ = 0;       // the node count then
  const Deadline deadline_;       // time_limit_s from the start, or the caller's deadline if sooner
  const Deadline hard_deadline_;  // the caller's deadline alone under time_limit_needs_incumbent
  NodeQueue queue_;
  BranchAndBoundResult result_;
  double unresolved_bound_ = kInfinity;
  double gap_pruned_bound_ = kInfinity;  // least bound of the subtrees pruned by the gap
  double in_flight_bound_ = kInfinity;   // least parent floor of the round being processed
  LaggingFloors lagging_;  // options.recertify_leaves
  Eigen::VectorXd restricted_lower_, restricted_upper_;  // Restrict (empty: none)
  bool restriction_asked_ = false;
};

// (objective - bound) / max(1, |objective|).
double RelativeGap(double objective, double bound);

}  // namespace mfp
