#include "planner/search/branch_and_bound.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "base/check.h"
#include "planner/search/internal/bound_propagation.h"
#include "planner/search/internal/branching.h"
#include "planner/search/internal/floor_recertification.h"
#include "planner/search/internal/group_probing.h"
#include "planner/search/internal/parallel_for.h"
#include "planner/search/internal/pseudo_costs.h"
#include "planner/search/internal/reduced_cost_fixing.h"
#include "planner/search/internal/reliability_branching.h"
#include "planner/search/internal/rins.h"
#include "planner/search/internal/root_cuts.h"
#include "planner/search/internal/search_heuristics.h"
#include "planner/search/internal/search_state.h"

namespace mfp {
namespace {

// The search loop: takes a round of open nodes (one per worker), evaluates them side by
// side (propagation, relaxation), then settles each: pruned, a new incumbent, or branched.
// The parts it composes: the node queue (node_queue.h), the branching rules
// (branching.h, reliability_branching.h), the rounding heuristic (search_heuristics.h)
// and the reduced-cost fixing (reduced_cost_fixing.h).

// Sets the bounds of each changed variable, in order (a later change of one variable wins).
void ApplyChanges(const std::vector<BoundChange>& changes, Eigen::VectorXd* lower, Eigen::VectorXd* upper) {
  for (const BoundChange& ch : changes) {
    (*lower)(ch.index) = ch.lower;
    (*upper)(ch.index) = ch.upper;
  }
}

// Along a path from the root each change of a variable's bounds is at least as tight as
// the ones before it: only the last one per variable counts. Keeps those, in order of the
// variables' first change (the probed bounds would otherwise pile up level by level).
void KeepLastChangePerVariable(int num_variables, std::vector<BoundChange>* changes) {
  std::vector<int> slot(num_variables, -1);
  std::vector<BoundChange> kept;
  kept.reserve(changes->size());
  for (const BoundChange& ch : *changes) {
    if (slot[ch.index] < 0) {
      slot[ch.index] = static_cast<int>(kept.size());
      kept.push_back(ch);
    } else {
      kept[slot[ch.index]] = ch;
    }
  }
  *changes = std::move(kept);
}

class Search {
 public:
  Search(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers, const BranchAndBoundOptions& options,
         const RoundingHeuristic& rounding)
      : p_(problem),
        opt_(options),
        rounding_(rounding),
        state_(problem, solvers, options),
        branching_(problem, options),
        pseudo_(problem.num_variables()),
        reliability_(&state_, &branching_, &pseudo_),
        rins_(options) {
    if (options.group_probing) prober_ = std::make_unique<GroupProber>(problem);
  }

  // A plan found before the search (the root cut loop's first pass) becomes its incumbent.
  // The plan of an earlier pass, held without a progress report (it was reported then,
  // and this search has no bound yet).
  void Seed(const Eigen::VectorXd& x) { state_.OfferIncumbent(x, /*report=*/false); }
  // The search ends (as at a node limit) after its root once it is long
  // (SearchState::IsLong): the root cut loop kept to long searches runs then.
  void StopOnceLong() { stop_once_long_ = true; }
  // Whether Run ended because the search became long (StopOnceLong), not on a limit.
  bool StoppedOnceLong() const { return stopped_once_long_; }
  // After Run: every node was processed (no open, unresolved or cut-short subtree).
  bool Exhausted() const { return exhausted_; }

  BranchAndBoundResult Run() {
    state_.queue().Push(SearchNode());
    do {
      SearchOpenNodes();
    } while (!hit_time_limit_ && !hit_node_limit_ && ReopenLaggingSubtree());
    return Finish();
  }

 private:
  // The search loop proper: rounds of open nodes until none is left or a limit ends it.
  void SearchOpenNodes() {
    NodeQueue& queue = state_.queue();
    const BranchAndBoundResult& result = state_.result();
    while (!queue.empty()) {
      if (state_.Active().Expired() || state_.Stalled()) {
        hit_time_limit_ = true;
        break;
      }
      if (result.nodes >= opt_.max_nodes) {
        hit_node_limit_ = true;
        break;
      }
      // The root heuristic that waited (root_heuristic_after_nodes), once its nodes are done.
      if (deferred_root_x_.size() > 0 && result.nodes >= opt_.root_heuristic_after_nodes) {
        const Eigen::VectorXd root_x = std::move(deferred_root_x_);
        deferred_root_x_.resize(0);
        RunDeferredRootHeuristic(&state_, root_x);
        continue;  // its plan may end the search: the limits and the queue are checked again
      }
      // Stopped once long only with a plan: the cut loop needs one, and without it the
      // second pass would start again from the root with nothing gained.
      if (stop_once_long_ && root_done_ && state_.IsLong() && state_.HasIncumbent()) {
        hit_node_limit_ = true;
        stopped_once_long_ = true;
        break;
      }
      std::vector<SearchNode> batch = TakeRound();
      double in_flight = kInfinity;
      for (const SearchNode& node : batch) in_flight = std::min(in_flight, node.parent_floor);
      state_.SetInFlightBound(in_flight);
      std::vector<NodeEvaluation> evaluations(batch.size());
      ForEachInParallel(static_cast<int>(batch.size()), [&](int k) {
        evaluations[k] = Evaluate(batch[k], state_.solver(k));
      });
      for (size_t k = 0; k < batch.size(); ++k) Process(batch[k], std::move(evaluations[k]));
      state_.SetInFlightBound(kInfinity);  // every node of the round is settled or back in the queue
    }
  }

  // An exhausted tree short of the gap by its floors (options.recertify_leaves): its
  // lowest settled subtrees are solved again (RecertifyLaggingFloors); one that may still
  // beat the incumbent is processed again from that solve, as a node, and true is returned
  // (its children, if any, are open). False when there is nothing to search again.
  bool ReopenLaggingSubtree() {
    if (!state_.queue().empty() || state_.HasUnresolved() || !state_.HasIncumbent() || opt_.recertify_leaves <= 0 ||
        !(state_.gap_pruned_bound() < state_.ProofFloor())) {
      return false;
    }
    std::optional<ReopenedSubtree> reopened = RecertifyLaggingFloors(&state_);
    if (!reopened) return false;
    SettledSubtree& subtree = reopened->subtree;
    SearchNode node;
    for (int j = 0; j < p_.num_variables(); ++j) {  // its box as changes from the root's
      if (subtree.lower(j) != p_.var_lower(j) || subtree.upper(j) != p_.var_upper(j)) {
        node.changes.push_back({j, subtree.lower(j), subtree.upper(j)});
      }
    }
    node.parent_floor = subtree.floor;
    node.depth = subtree.depth;
    node.parent_objective = reopened->relaxation.objective;
    NodeEvaluation e;
    e.lower = std::move(subtree.lower);
    e.upper = std::move(subtree.upper);
    e.relaxation = std::move(reopened->relaxation);  // its solve is counted (floor_recertifications)
    Process(node, std::move(e));
    return true;
  }

  // A node's bounds after propagation and its relaxation: the part of a node's work that
  // touches nothing shared, so that several nodes can be evaluated at once.
  struct NodeEvaluation {
    Eigen::VectorXd lower, upper;
    bool propagation_infeasible = false;
    bool probed = false;  // lower/upper hold probed bounds, to be handed to the children
    RelaxationResult relaxation;
    int solves = 0;
    int iterations = 0;    // of its solves
    double solve_s = 0.0;  // wall time of its solves
    int fallbacks = 0;        // of its solves, those the solver's fallback solved
    double fallback_s = 0.0;  // their wall time
    int polished = 0, polish_attempts = 0;  // of its solves (RelaxationResult)

    // Takes solve r as the node's relaxation and adds its work to the counts.
    void TakeSolve(RelaxationResult r) {
      relaxation = std::move(r);
      ++solves;
      iterations += relaxation.iterations;
      fallbacks += relaxation.fallbacks;
      fallback_s += relaxation.fallback_time_s;
      polished += relaxation.polished;
      polish_attempts += relaxation.polish_attempts;
    }
  };

  // Up to one node per worker: their relaxations are solved side by side, then the nodes
  // are processed one after the other in the order they were chosen. The root alone.
  std::vector<SearchNode> TakeRound() {
    NodeQueue& queue = state_.queue();
    std::vector<SearchNode> batch;
    while (!queue.empty() && static_cast<int>(batch.size()) < state_.workers() &&
           state_.result().nodes + static_cast<int>(batch.size()) < opt_.max_nodes) {
      SearchNode node = queue.Pop(state_.HasIncumbent(), state_.result().objective);
      if (state_.HasIncumbent() && !state_.Improves(node.parent_bound)) {
        NoteUnsolvedPrune(node);
        continue;
      }
      batch.push_back(std::move(node));
      if (!root_done_) break;
    }
    return batch;
  }

  NodeEvaluation Evaluate(const SearchNode& node, RelaxationSolver& solver) const {
    NodeEvaluation e;
    e.lower = p_.var_lower;
    e.upper = p_.var_upper;
    ApplyChanges(node.changes, &e.lower, &e.upper);
    if (opt_.bound_propagation && PropagateBounds(p_, &e.lower, &e.upper).infeasible) {
      e.propagation_infeasible = true;
      return e;
    }
    if (ProbingDue(node.depth)) {
      e.probed = true;
      if (Probe(node, &e.lower, &e.upper)) {
        e.propagation_infeasible = true;
        return e;
      }
    }
    const Eigen::VectorXd* warm = node.warm_start.size() ? &node.warm_start : nullptr;
    // A node whose relaxation cannot beat the incumbent is pruned: its solve may stop as
    // soon as that is proven.
    const double cutoff = state_.HasIncumbent() ? state_.result().objective - state_.GapTolerance() : kInfinity;
    const auto start = std::chrono::steady_clock::now();
    RelaxationRequest request = state_.Request(e.lower, e.upper, warm, cutoff);
    request.warm_token = node.warm_token;
    e.TakeSolve(solver.Solve(p_, request));
    if (e.relaxation.status != RelaxationStatus::kSolved && e.relaxation.status != RelaxationStatus::kCutoff &&
        warm != nullptr) {
      e.TakeSolve(state_.SolveWith(solver, e.lower, e.upper, nullptr));  // a bad warm start can stall Ipopt
    }
    e.solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return e;
  }

  void Process(const SearchNode& node, NodeEvaluation e) {
    BranchAndBoundResult& result = state_.result();
    ++result.nodes;
    result.relaxations += e.solves;
    result.node_solve_iterations += e.iterations;
    result.node_solve_time_s += e.solve_s;
    result.node_fallbacks += e.fallbacks;
    result.fallbacks += e.fallbacks;
    result.fallback_time_s += e.fallback_s;
    result.node_polished += e.polished;
    result.node_polish_attempts += e.polish_attempts;
    const bool is_root = !root_done_;
    root_done_ = true;
    if (e.propagation_infeasible) {
      ++result.propagation_prunes;
      if (is_root) root_infeasible_ = true;
      return;
    }
    const RelaxationResult& rel = e.relaxation;
    if (rel.status == RelaxationStatus::kInfeasible) {
      if (is_root) root_infeasible_ = true;
      return;
    }
    if (rel.status == RelaxationStatus::kCutoff) {  // proven not to beat the incumbent
      ++result.early_cutoffs;
      const double floor = std::max(rel.objective, node.parent_floor);  // a cutoff's objective is its floor
      if (is_root) result.bound = result.root_bound = floor;
      NoteSettled(floor, node.depth, e, nullptr);
      return;
    }
    if (rel.status != RelaxationStatus::kSolved) {
      // Cannot bound this subtree: drop it and remember that optimality is unproven.
      state_.NoteUnresolved(node.parent_floor);
      if (is_root) root_failed_ = true;
      return;
    }
    if (node.branch_var >= 0) {
      pseudo_.Record(node.branch_var, node.branch_up, rel.objective - node.parent_objective, node.branch_distance);
    }
    // The objective orders and prunes; the subtree's bound, as claimed, is what the solve
    // certifies (an interior point accepted at a coarse dual residual certifies less than
    // its objective): a subtree pruned by its objective counts at its floor.
    const double bound = std::max(rel.objective, node.parent_bound);
    const double floor = std::max(rel.CertifiedFloor(), node.parent_floor);
    if (opt_.equivalent_point) UseEquivalentPoint(e.lower, e.upper, &e.relaxation.x);
    if (is_root) {
      result.bound = result.root_bound = floor;
      TryRounding(&state_, branching_, rounding_, rel.x);
      if (RunRootHeuristic(&state_, rel.x)) deferred_root_x_ = rel.x;
    }
    if (state_.HasIncumbent() && !state_.Improves(bound)) {
      NoteSettled(floor, node.depth, e, &rel.x);
      return;
    }
    if (is_root) {
      ProbeRootAfterHeuristics(node, &e);
      if (rins_.DueAtRoot(state_) && state_.LeverPays(kLongSearchRins)) Rins(rel.x);
    }
    std::vector<BoundChange> fixings;
    if (opt_.reduced_cost_fixing && state_.HasIncumbent()) FixByReducedCosts(rel, &state_, &e.lower, &e.upper, &fixings);
    const int branch_var = opt_.branching == BranchingRule::kReliability
                               ? reliability_.Choose(rel, e.lower, e.upper)
                               : branching_.ChooseVariable(rel.x, e.lower, e.upper);
    if (branch_var == kPruned) return;
    if (branch_var < 0) {
      // Probing after the root's relaxation may have fixed every integer the relaxation
      // point left fractional: then the root is solved again in the probed box.
      if (is_root && e.probed && !IsIntegral(rel.x)) {
        SolveRootAgain(node, rel, bound, floor, e.lower, e.upper, fixings);
        return;
      }
      state_.OfferIncumbent(rel.x);
      NoteSettled(floor, node.depth, e, &rel.x);  // the subtree is closed at its floor
      return;
    }
    if (opt_.rounding_heuristic && opt_.rounding_frequency > 0 && result.nodes % opt_.rounding_frequency == 0) {
      TryRounding(&state_, branching_, rounding_, rel.x);
    }
    if (!is_root && rins_.DueAtNode(state_) && state_.LeverPays(kLongSearchRins)) {
      Rins(rel.x);
    }
    if (e.probed) {
      ++result.probed_nodes;
      AppendProbedBounds(node, e.lower, e.upper, &fixings);
    }
    Branch(node, rel, bound, floor, branch_var, e.lower, e.upper, fixings);
  }

  // A solved node's subtree settled at `floor` (pruned or closed), with its evaluated box
  // and relaxation point for re-certification (options.recertify_leaves).
  void NoteSettled(double floor, int depth, const NodeEvaluation& e, const Eigen::VectorXd* relaxed) {
    if (!state_.KeepsForRecertification(floor)) {
      state_.NoteGapPrune(floor);
      return;
    }
    SettledSubtree subtree;
    subtree.floor = floor;
    subtree.lower = e.lower;
    subtree.upper = e.upper;
    if (relaxed != nullptr) subtree.relaxed = *relaxed;
    subtree.propagated = true;
    subtree.depth = depth;
    state_.NoteGapPrune(std::move(subtree));
  }

  // An open node pruned by its parent's bound before its own relaxation: its subtree
  // counts at its parent's floor, its box the bound changes from the root.
  void NoteUnsolvedPrune(const SearchNode& node) {
    if (!state_.KeepsForRecertification(node.parent_floor)) {
      state_.NoteGapPrune(node.parent_floor);
      return;
    }
    SettledSubtree subtree;
    subtree.floor = node.parent_floor;
    subtree.lower = p_.var_lower;
    subtree.upper = p_.var_upper;
    ApplyChanges(node.changes, &subtree.lower, &subtree.upper);
    subtree.relaxed = node.warm_start;
    subtree.depth = node.depth;
    state_.NoteGapPrune(std::move(subtree));
  }

  bool IsIntegral(const Eigen::VectorXd& x) const {
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (p_.is_integer[j] && std::abs(x(j) - std::round(x(j))) > opt_.integrality_tolerance) return false;
    }
    return true;
  }

  // Queues the root once more with its probed box (lower/upper) as bound changes.
  void SolveRootAgain(const SearchNode& root, const RelaxationResult& rel, double bound, double floor,
                      const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, std::vector<BoundChange> fixings) {
    AppendProbedBounds(root, lower, upper, &fixings);
    SearchNode again;
    again.changes = root.changes;
    again.changes.insert(again.changes.end(), fixings.begin(), fixings.end());
    KeepLastChangePerVariable(p_.num_variables(), &again.changes);
    again.parent_bound = bound;
    again.parent_floor = floor;
    again.depth = root.depth;  // not probed again before its relaxation
    again.warm_start = rel.x;
    again.warm_token = rel.warm_token;
    again.parent_objective = rel.objective;
    std::vector<SearchNode> pushed;
    pushed.push_back(std::move(again));
    state_.queue().PushChildren(std::move(pushed));
  }

  void Rins(const Eigen::VectorXd& relaxed) {
    const double objective_before = state_.result().objective;
    const RinsOutcome outcome = RunRins(&state_, relaxed, rounding_);
    rins_.Record(state_, outcome, objective_before);
    BranchAndBoundResult& result = state_.result();
    result.rins_runs += outcome.ran ? 1 : 0;
    result.rins_improvements += outcome.improved ? 1 : 0;
    result.rins_nodes += outcome.nodes;
  }

  bool ProbingDue(int depth) const {
    return prober_ && depth >= 1 && (depth - 1) % std::max(1, opt_.group_probing_interval) == 0 &&
           state_.LeverPays(kLongSearchProbing);
  }

  // Probes the box lower/upper of `node` under the work cap and the deadline in force;
  // true when it proves the node infeasible.
  bool Probe(const SearchNode& node, Eigen::VectorXd* lower, Eigen::VectorXd* upper) const {
    GroupProbingLimits limits;
    if (opt_.group_probing_work > 0.0) {
      limits.max_row_visits = static_cast<long>(std::ceil(opt_.group_probing_work * std::max(1, p_.num_rows())));
    }
    limits.deadline = state_.Active();
    limits.centre_group = node.branch_var >= 0 ? branching_.GroupOf(node.branch_var) : -1;
    return prober_->Probe(lower, upper, limits).infeasible;
  }

  // The root is probed only once its roundings and heuristics have run, so that probing
  // never delays the first plan; its bounds reach the root's children. A root box that
  // probing finds empty (only possible within tolerances, as the search may hold a plan)
  // is left as it was.
  void ProbeRootAfterHeuristics(const SearchNode& root, NodeEvaluation* e) {
    if (!prober_ || state_.Active().Expired() || !state_.LeverPays(kLongSearchProbing)) return;
    Eigen::VectorXd lower = e->lower, upper = e->upper;
    if (Probe(root, &lower, &upper)) return;
    e->lower = std::move(lower);
    e->upper = std::move(upper);
    e->probed = true;
  }

  // The bounds of a probed node that are tighter than its changes from the root, as
  // changes for its children to inherit.
  void AppendProbedBounds(const SearchNode& node, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                          std::vector<BoundChange>* changes) const {
    Eigen::VectorXd base_lower = p_.var_lower, base_upper = p_.var_upper;
    ApplyChanges(node.changes, &base_lower, &base_upper);
    ApplyChanges(*changes, &base_lower, &base_upper);
    constexpr double kMinTightening = 1e-9;
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (lower(j) > base_lower(j) + kMinTightening || upper(j) < base_upper(j) - kMinTightening) {
        changes->push_back({j, lower(j), upper(j)});
      }
    }
  }

  // The caller's equivalent of a relaxation point, when it meets the node's rows and
  // bounds and costs no more.
  void UseEquivalentPoint(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd* x) {
    Eigen::VectorXd y = *x;
    if (!opt_.equivalent_point(lower, upper, &y)) return;
    const double tol = opt_.feasibility_tolerance;
    if ((y.array() < lower.array() - tol).any() || (y.array() > upper.array() + tol).any()) return;
    if (p_.MaxViolationOfRows(y) > std::max(tol, p_.MaxViolationOfRows(*x))) return;
    const double before = p_.Objective(*x);
    if (p_.Objective(y) > before + 1e-9 * (1.0 + std::abs(before))) return;
    *x = std::move(y);
    ++state_.result().equivalent_points;
  }

  // Both children of branching on j; the one towards the relaxation's rounding is pushed
  // last, so that a dive explores it first.
  void Branch(const SearchNode& node, const RelaxationResult& rel, double bound, double floor, int j,
              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const std::vector<BoundChange>& fixings) {
    const Eigen::VectorXd& x = rel.x;
    const double floor_v = std::floor(x(j) + opt_.integrality_tolerance);
    SearchNode children[2];  // down, up
    bool valid[2];
    for (int up = 0; up < 2; ++up) {
      SearchNode& child = children[up];
      child.changes = node.changes;
      child.changes.insert(child.changes.end(), fixings.begin(), fixings.end());
      if (prober_) KeepLastChangePerVariable(p_.num_variables(), &child.changes);
      child.parent_bound = bound;
      child.parent_floor = floor;
      child.depth = node.depth + 1;
      child.warm_start = x;
      child.warm_token = rel.warm_token;
      child.branch_var = j;
      child.branch_up = up == 1;
      child.parent_objective = rel.objective;
      Eigen::VectorXd l = lower, u = upper;
      child.branch_distance = branching_.ChildBounds(j, x(j), up == 1, &l, &u, &child.changes);
      valid[up] = child.branch_distance > 0.0;
    }
    const bool up_first = x(j) - floor_v >= 0.5 || branching_.GroupOf(j) >= 0;
    const int first = up_first ? 1 : 0;
    std::vector<SearchNode> pushed;
    if (valid[1 - first]) pushed.push_back(std::move(children[1 - first]));
    if (valid[first]) pushed.push_back(std::move(children[first]));
    state_.queue().PushChildren(std::move(pushed));
  }

  BranchAndBoundResult Finish() {
    BranchAndBoundResult& result = state_.result();
    const bool open = !state_.queue().empty();
    result.solve_time_s = state_.Elapsed();
    // A relaxation the deadline cut short left its subtree unresolved: that is the time
    // limit, not a solver failure.
    if (state_.Active().Expired() && (root_failed_ || state_.HasUnresolved() || open)) hit_time_limit_ = true;
    exhausted_ = !open && !hit_time_limit_ && !hit_node_limit_ && !state_.HasUnresolved();
    const double open_bound = state_.UnexploredBound();
    if (state_.HasIncumbent()) {
      result.bound = std::min(result.objective, std::max(result.bound, open_bound));
      if (!open && !state_.HasUnresolved()) result.bound = std::min(result.objective, state_.gap_pruned_bound());
      result.gap = RelativeGap(result.objective, result.bound);
      // Optimal only when the certified bound proves the gap asked: subtrees pruned by
      // their objectives count at their floors, which may leave an exhausted tree short.
      const bool proven = result.gap <= opt_.relative_gap || result.objective - result.bound <= opt_.absolute_gap;
      if (proven && !state_.HasUnresolved()) {
        result.status = SolveStatus::kOptimal;
      } else {
        result.status = hit_time_limit_ ? SolveStatus::kTimeLimit : SolveStatus::kFeasible;
      }
    } else if (root_infeasible_ || exhausted_) {
      result.status = SolveStatus::kInfeasible;
      result.bound = kInfinity;
    } else if (root_failed_ && !hit_time_limit_) {
      result.status = SolveStatus::kInternalError;
    } else {
      result.status = SolveStatus::kNoSolution;
      result.bound = std::max(result.bound, open_bound == kInfinity ? result.bound : open_bound);
    }
    return result;
  }

  const Miqp& p_;
  const BranchAndBoundOptions& opt_;
  const RoundingHeuristic& rounding_;
  SearchState state_;
  Branching branching_;
  PseudoCosts pseudo_;
  ReliabilityBranching reliability_;
  std::unique_ptr<GroupProber> prober_;  // with options.group_probing
  RinsSchedule rins_;
  // The root relaxation point while root_heuristic waits (root_heuristic_after_nodes);
  // empty otherwise.
  Eigen::VectorXd deferred_root_x_;
  bool root_done_ = false;
  bool stop_once_long_ = false;
  bool stopped_once_long_ = false;
  bool exhausted_ = false;
  bool hit_time_limit_ = false;
  bool hit_node_limit_ = false;
  bool root_infeasible_ = false;
  bool root_failed_ = false;
};

// Adds the work counters of an earlier pass to `total` (nodes, solves, prunes, heuristics).
void AddCounters(const BranchAndBoundResult& pass, BranchAndBoundResult* total) {
  total->nodes += pass.nodes;
  total->relaxations += pass.relaxations;
  total->strong_branching_solves += pass.strong_branching_solves;
  total->propagation_prunes += pass.propagation_prunes;
  total->early_cutoffs += pass.early_cutoffs;
  total->reduced_cost_fixings += pass.reduced_cost_fixings;
  total->equivalent_points += pass.equivalent_points;
  total->node_solve_iterations += pass.node_solve_iterations;
  total->node_solve_time_s += pass.node_solve_time_s;
  total->node_fallbacks += pass.node_fallbacks;
  total->fallbacks += pass.fallbacks;
  total->fallback_time_s += pass.fallback_time_s;
  total->node_polished += pass.node_polished;
  total->node_polish_attempts += pass.node_polish_attempts;
  total->floor_recertifications += pass.floor_recertifications;
  total->floors_certified += pass.floors_certified;
  total->probed_nodes += pass.probed_nodes;
  total->rins_runs += pass.rins_runs;
  total->rins_improvements += pass.rins_improvements;
  total->rins_nodes += pass.rins_nodes;
}

// options with its time limit shortened by spent_s and its progress times shifted by it.
BranchAndBoundOptions Remaining(const BranchAndBoundOptions& options, double spent_s) {
  BranchAndBoundOptions rest = options;
  rest.time_limit_s = std::max(0.0, options.time_limit_s - spent_s);
  if (options.on_incumbent) {
    rest.on_incumbent = [&options, spent_s](const BranchAndBoundResult& so_far) {
      BranchAndBoundResult shifted = so_far;
      shifted.solve_time_s += spent_s;
      options.on_incumbent(shifted);
    };
  }
  return rest;
}

// The search with the root cut loop (BranchAndBoundOptions::root_cut_rounds): the root
// alone first (relaxation, roundings, heuristics) on the problem as given, so that the
// loop cannot delay the first plan; then the loop, with reduced-cost fixing against that
// plan; then the search on the problem with the cuts, holding that plan.
BranchAndBoundResult SolveWithRootCuts(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers,
                                       const BranchAndBoundOptions& options, const RoundingHeuristic& extra_rounding) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const Deadline deadline = options.deadline.Within(options.time_limit_s);  // the whole search's
  // The first pass: the root alone, or with the loop kept to long searches, the search
  // until it is long (a search that ends sooner never runs the loop).
  const bool until_long = (options.long_search_only & kLongSearchRootCuts) != 0;
  BranchAndBoundOptions first_pass = options;
  first_pass.root_cut_rounds = 0;
  first_pass.root_heuristic_after_nodes = 0;  // the second pass runs no root heuristic
  if (!until_long) {
    first_pass.max_nodes = 1;
    first_pass.group_probing = false;  // its children are not searched: the second pass probes
    first_pass.rins_frequency = 0;
  }
  Search first(problem, solvers, first_pass, extra_rounding);
  if (until_long) first.StopOnceLong();
  BranchAndBoundResult root = first.Run();
  root.solve_time_s = elapsed();
  const bool settled = root.status == SolveStatus::kOptimal || root.status == SolveStatus::kInfeasible ||
                       root.status == SolveStatus::kInternalError;
  // A first pass that exhausted its tree (an integral root whose certified floor misses
  // the gap asked) is the answer too: cuts tighten open nodes, and there is none; a second
  // pass would solve the same root to the same floor.
  if (settled || first.Exhausted() || root.nodes >= options.max_nodes) return root;
  // A first pass kept to long searches that ended on its stall limit (not because it
  // became long) is the search's answer: a second pass would give it a second stall window.
  if (until_long && !first.StoppedOnceLong()) return root;
  if (deadline.Expired()) {
    if (root.status == SolveStatus::kFeasible) root.status = SolveStatus::kTimeLimit;
    return root;
  }
  const bool has_plan = root.x.size() > 0;
  // Without a plan the search's dives must find one first: no cuts then.
  RootCutLoopResult loop;
  if (has_plan) {
    loop = RunRootCutLoop(problem, *solvers.front(), options, deadline, root.objective);
  } else {
    loop.problem = problem;
  }
  // The heuristics have run at the first root: the search's root reruns only its roundings.
  BranchAndBoundOptions rest = Remaining(options, elapsed());
  rest.max_nodes = options.max_nodes - root.nodes;
  rest.root_heuristic = nullptr;
  rest.first_plan_heuristic = nullptr;
  Search search(loop.problem, solvers, rest, extra_rounding);
  if (has_plan) search.Seed(root.x);
  BranchAndBoundResult result = search.Run();
  if (has_plan && (result.x.size() == 0 || root.objective < result.objective)) {  // the plan did not meet the cut problem
    result.x = root.x;
    result.objective = root.objective;
    result.bound = std::min(result.bound, root.objective);
    result.gap = RelativeGap(result.objective, result.bound);
    if (result.status == SolveStatus::kNoSolution || result.status == SolveStatus::kInfeasible) {
      result.status = SolveStatus::kFeasible;
    }
  }
  result.root_cuts = loop.cuts;
  result.root_bound_before_cuts = root.root_bound;
  // The first pass's root bound holds for the problem: the second may end before its root.
  if (result.x.size() > 0) result.bound = std::min(result.objective, std::max(result.bound, root.bound));
  result.gap = result.x.size() > 0 ? RelativeGap(result.objective, result.bound) : result.gap;
  AddCounters(root, &result);
  result.relaxations += loop.relaxations;
  result.fallbacks += loop.fallbacks;
  result.fallback_time_s += loop.fallback_time_s;
  result.reduced_cost_fixings += loop.reduced_cost_fixings;
  result.solve_time_s = elapsed();
  return result;
}

}  // namespace

BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding) {
  CheckMiqpShape(problem);
  MFP_CHECK_MSG(!solvers.empty(), "branch-and-bound needs at least one relaxation solver");
  for (const RelaxationSolver* s : solvers) MFP_CHECK(s != nullptr);
  if (options.root_cut_rounds <= 0 || problem.num_integer() == 0) {
    Search search(problem, solvers, options, extra_rounding);
    return search.Run();
  }
  return SolveWithRootCuts(problem, solvers, options, extra_rounding);
}

BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, RelaxationSolver& solver,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding) {
  return SolveBranchAndBound(problem, std::vector<RelaxationSolver*>{&solver}, options, extra_rounding);
}

}  // namespace mfp
