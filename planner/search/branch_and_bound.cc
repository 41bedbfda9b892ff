#include "planner/search/branch_and_bound.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "planner/base/check.h"
#include "planner/qp/fixed_integer_qp.h"
#include "planner/search/bound_propagation.h"
#include "planner/search/pseudo_costs.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kPruned = -2;           // a branching choice that proved the node empty
constexpr double kLargeGain = 1e12;   // stands in for an empty child in a product score

struct BoundChange {
  int index;
  double lower, upper;
};

// A node is its parent's bound plus the bound changes from the root; the tree keeps the
// open nodes, the search loop owns the rest.
struct Node {
  std::vector<BoundChange> changes;
  double parent_bound = -kInfinity;
  int depth = 0;
  // The branching that made this node, for the pseudo-costs.
  int branch_var = -1;
  bool branch_up = false;
  double branch_distance = 0.0;
  double parent_objective = 0.0;
  Eigen::VectorXd warm_start;  // parent's relaxation point
};

class Search {
 public:
  Search(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers, const BranchAndBoundOptions& options,
         const RoundingHeuristic& rounding)
      : p_(problem),
        solvers_(solvers),
        opt_(options),
        rounding_(rounding),
        start_(Clock::now()),
        deadline_(options.deadline.Within(options.time_limit_s)),
        hard_deadline_(options.time_limit_needs_incumbent ? options.deadline : deadline_),
        pseudo_(problem.num_variables()) {
    group_of_.assign(p_.num_variables(), -1);
    for (size_t g = 0; g < p_.sos1_groups.size(); ++g) {
      for (int j : p_.sos1_groups[g]) group_of_[j] = static_cast<int>(g);
    }
  }

  BranchAndBoundResult Run() {
    Node root;
    open_.push_back(std::move(root));
    const int workers = static_cast<int>(solvers_.size());
    while (!open_.empty()) {
      if (Active().Expired() || Stalled()) {
        hit_time_limit_ = true;
        break;
      }
      if (result_.nodes >= opt_.max_nodes) {
        hit_node_limit_ = true;
        break;
      }
      // Up to one node per worker: their relaxations are solved side by side, then the
      // nodes are processed one after the other in the order they were chosen.
      std::vector<Node> batch;
      while (!open_.empty() && static_cast<int>(batch.size()) < workers &&
             result_.nodes + static_cast<int>(batch.size()) < opt_.max_nodes) {
        Node node = PopNode();
        if (HasIncumbent() && !Improves(node.parent_bound)) {
          NoteGapPrune(node.parent_bound);
          continue;
        }
        batch.push_back(std::move(node));
        if (!root_done_) break;  // the root alone
      }
      for (const Node& node : batch) in_flight_bound_ = std::min(in_flight_bound_, node.parent_bound);
      std::vector<NodeEvaluation> evaluations(batch.size());
      ForEachInParallel(static_cast<int>(batch.size()), [&](int k) {
        evaluations[k] = Evaluate(batch[k], *solvers_[k]);
      });
      for (size_t k = 0; k < batch.size(); ++k) Process(batch[k], std::move(evaluations[k]));
      in_flight_bound_ = kInfinity;  // every node of the round is settled or back in open_
    }
    return Finish();
  }

 private:
  // A node's bounds after propagation and its relaxation: the part of a node's work that
  // touches nothing shared, so that several nodes can be evaluated at once.
  struct NodeEvaluation {
    Eigen::VectorXd lower, upper;
    bool propagation_infeasible = false;
    RelaxationResult relaxation;
    int solves = 0;
  };

  NodeEvaluation Evaluate(const Node& node, RelaxationSolver& solver) const {
    NodeEvaluation e;
    e.lower = p_.var_lower;
    e.upper = p_.var_upper;
    for (const BoundChange& ch : node.changes) {
      e.lower(ch.index) = ch.lower;
      e.upper(ch.index) = ch.upper;
    }
    if (opt_.bound_propagation && PropagateBounds(p_, &e.lower, &e.upper).infeasible) {
      e.propagation_infeasible = true;
      return e;
    }
    const Eigen::VectorXd* warm = node.warm_start.size() ? &node.warm_start : nullptr;
    // A node whose relaxation cannot beat the incumbent is pruned: its solve may stop as
    // soon as that is proven.
    const double cutoff = HasIncumbent() ? result_.objective - GapTolerance() : kInfinity;
    e.relaxation = SolveWith(solver, e.lower, e.upper, warm, cutoff);
    ++e.solves;
    if (e.relaxation.status != RelaxationStatus::kSolved && e.relaxation.status != RelaxationStatus::kCutoff &&
        warm != nullptr) {
      e.relaxation = SolveWith(solver, e.lower, e.upper, nullptr);  // a bad warm start can stall Ipopt
      ++e.solves;
    }
    return e;
  }

  // Runs task(0 .. count-1), task(k) on a thread of its own for k >= 1.
  template <typename Task>
  static void ForEachInParallel(int count, const Task& task) {
    std::vector<std::thread> threads;
    for (int k = 1; k < count; ++k) threads.emplace_back([&task, k] { task(k); });
    if (count > 0) task(0);
    for (std::thread& t : threads) t.join();
  }

  void Process(const Node& node, NodeEvaluation e) {
    ++result_.nodes;
    result_.relaxations += e.solves;
    const bool is_root = !root_done_;
    root_done_ = true;
    if (e.propagation_infeasible) {
      ++result_.propagation_prunes;
      if (is_root) root_infeasible_ = true;
      return;
    }
    const RelaxationResult& rel = e.relaxation;
    if (rel.status == RelaxationStatus::kInfeasible) {
      if (is_root) root_infeasible_ = true;
      return;
    }
    if (rel.status == RelaxationStatus::kCutoff) {  // proven not to beat the incumbent
      ++result_.early_cutoffs;
      const double bound = std::max(rel.objective, node.parent_bound);
      if (is_root) result_.bound = result_.root_bound = bound;
      NoteGapPrune(bound);
      return;
    }
    if (rel.status != RelaxationStatus::kSolved) {
      // Cannot bound this subtree: drop it and remember that optimality is unproven.
      unresolved_bound_ = std::min(unresolved_bound_, node.parent_bound);
      if (is_root) root_failed_ = true;
      return;
    }
    if (node.branch_var >= 0) {
      pseudo_.Record(node.branch_var, node.branch_up, rel.objective - node.parent_objective, node.branch_distance);
    }
    const double bound = std::max(rel.objective, node.parent_bound);
    if (opt_.equivalent_point) UseEquivalentPoint(e.lower, e.upper, &e.relaxation.x);
    if (is_root) {
      result_.bound = result_.root_bound = bound;
      TryRounding(rel.x);
    }
    if (HasIncumbent() && !Improves(bound)) {
      NoteGapPrune(bound);
      return;
    }
    std::vector<BoundChange> fixings;
    if (opt_.reduced_cost_fixing && HasIncumbent()) FixByReducedCosts(rel, &e.lower, &e.upper, &fixings);
    const int branch_var = opt_.branching == BranchingRule::kReliability
                               ? ChooseByReliability(rel, &e.lower, &e.upper)
                               : ChooseBranchVariable(rel.x, e.lower, e.upper);
    if (branch_var == kPruned) return;
    if (branch_var < 0) {
      OfferIncumbent(rel.x);
      return;
    }
    if (opt_.rounding_heuristic && opt_.rounding_frequency > 0 && result_.nodes % opt_.rounding_frequency == 0) {
      TryRounding(rel.x);
    }
    Branch(node, rel, bound, branch_var, e.lower, e.upper, fixings);
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
    ++result_.equivalent_points;
  }

  // Integer values whose subtree cannot beat the incumbent by more than the gap, by the
  // relaxation's reduced-cost certificate: x_j >= l_j + t costs at least
  // floor + rate_l t (likewise below u_j). Tightened bounds go to both children; the
  // bound of what they rule out is kept for the final gap.
  void FixByReducedCosts(const RelaxationResult& rel, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                         std::vector<BoundChange>* fixings) {
    if (rel.lower_cost_rate.size() != p_.num_variables() || !std::isfinite(rel.cost_floor)) return;
    const double room = result_.objective - GapTolerance() - rel.cost_floor;  // objective increase still allowed
    if (room < 0.0) return;
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (!p_.is_integer[j] || (*lower)(j) >= (*upper)(j)) continue;
      double lo = (*lower)(j), hi = (*upper)(j);
      const double up_rate = rel.lower_cost_rate(j), down_rate = rel.upper_cost_rate(j);
      if (up_rate > 0.0 && lo + room / up_rate < hi) {
        const double new_hi = std::floor(lo + room / up_rate + opt_.integrality_tolerance);
        if (new_hi < hi) {
          NoteGapPrune(rel.cost_floor + up_rate * (new_hi + 1.0 - lo));
          hi = new_hi;
        }
      }
      if (down_rate > 0.0 && hi - room / down_rate > lo) {
        const double new_lo = std::ceil(hi - room / down_rate - opt_.integrality_tolerance);
        if (new_lo > lo) {
          NoteGapPrune(rel.cost_floor + down_rate * ((*upper)(j) - (new_lo - 1.0)));
          lo = new_lo;
        }
      }
      if (lo == (*lower)(j) && hi == (*upper)(j)) continue;
      ++result_.reduced_cost_fixings;
      fixings->push_back({j, lo, hi});
      (*lower)(j) = lo;
      (*upper)(j) = hi;
    }
  }

 private:
  // The deadline in force: the time limit's, or before the first incumbent under
  // time_limit_needs_incumbent the caller's alone.
  const Deadline& Active() const { return !HasIncumbent() ? hard_deadline_ : deadline_; }

  double Elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  bool HasIncumbent() const { return result_.x.size() > 0; }
  // BranchAndBoundOptions::stall_time_fraction.
  bool Stalled() const {
    return opt_.stall_time_fraction > 0.0 && HasIncumbent() &&
           std::chrono::duration<double>(Clock::now() - last_improvement_).count() >
               opt_.stall_time_fraction * opt_.time_limit_s;
  }

  // True when a subtree with this bound may still beat the incumbent by more than the gap.
  bool Improves(double bound) const { return bound < result_.objective - GapTolerance(); }

  // How much better than the incumbent a subtree must be able to get to be explored.
  double GapTolerance() const {
    return std::max(opt_.absolute_gap, opt_.relative_gap * std::max(1.0, std::abs(result_.objective)));
  }

  // A subtree dropped because it cannot beat the incumbent by more than the gap still
  // bounds the optimum: the reported bound must not rise above it.
  void NoteGapPrune(double bound) { gap_pruned_bound_ = std::min(gap_pruned_bound_, bound); }

  // The request for one relaxation under the deadline in force.
  RelaxationRequest Request(Eigen::VectorXd lower, Eigen::VectorXd upper, const Eigen::VectorXd* warm,
                            double cutoff = kInfinity) const {
    RelaxationRequest request;
    request.lower = std::move(lower);
    request.upper = std::move(upper);
    if (warm != nullptr) request.warm_start = *warm;
    request.deadline = Active();
    if (opt_.early_cutoff) request.cutoff = cutoff;
    request.relative_tolerance = opt_.relaxation_tolerance;
    return request;
  }

  RelaxationResult SolveWith(RelaxationSolver& solver, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                             const Eigen::VectorXd* warm, double cutoff = kInfinity) const {
    return solver.Solve(p_, Request(lower, upper, warm, cutoff));
  }

  Node PopNode() {
    size_t pick = open_.size() - 1;  // depth first: newest
    const bool plunge = just_branched_ && PlungeContinues(open_.back().parent_bound);
    just_branched_ = false;
    const bool best_bound = opt_.node_selection == NodeSelection::kBestBound ||
                            (opt_.node_selection == NodeSelection::kDiveThenBestBound && HasIncumbent()) ||
                            (opt_.node_selection == NodeSelection::kBestBoundWithPlunging && !plunge);
    if (best_bound) {
      for (size_t k = 0; k < open_.size(); ++k) {
        const Node& a = open_[k];
        const Node& b = open_[pick];
        if (a.parent_bound < b.parent_bound - 1e-12 ||
            (std::abs(a.parent_bound - b.parent_bound) <= 1e-12 && a.depth > b.depth)) {
          pick = k;
        }
      }
    }
    Node node = std::move(open_[pick]);
    open_[pick] = std::move(open_.back());
    open_.pop_back();
    return node;
  }

  // Plunging: the newest node is the child just pushed; go on with it while its bound is
  // close enough to the best open bound, measured against the incumbent.
  bool PlungeContinues(double child_bound) const {
    if (opt_.node_selection != NodeSelection::kBestBoundWithPlunging) return false;
    if (!HasIncumbent()) return true;
    double best = child_bound;
    for (const Node& n : open_) best = std::min(best, n.parent_bound);
    return child_bound <= best + opt_.plunge_fraction * (result_.objective - best);
  }

  double Fractionality(double v) const { return std::abs(v - std::round(v)); }

  // The integer variable to branch on, or -1 when x is integral.
  int ChooseBranchVariable(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                           const Eigen::VectorXd& upper) const {
    if (opt_.branching == BranchingRule::kGroupOrder) {
      for (const auto& group : p_.sos1_groups) {
        int best = -1;
        double best_score = opt_.integrality_tolerance;
        for (int j : group) {
          if (lower(j) >= upper(j)) continue;
          const double f = Fractionality(x(j));
          if (f > best_score) {
            best_score = f;
            best = j;
          }
        }
        if (best >= 0) return best;
      }
    }
    if (opt_.branching == BranchingRule::kSos1Split) {
      // The group with the most fractional member; branch on that member (its up child
      // fixes the whole group).
      int best = -1;
      double best_score = opt_.integrality_tolerance;
      for (const auto& group : p_.sos1_groups) {
        for (int j : group) {
          if (lower(j) >= upper(j)) continue;
          const double f = Fractionality(x(j));
          if (f > best_score + 1e-12 || (best >= 0 && std::abs(f - best_score) <= 1e-12 && x(j) > x(best))) {
            best_score = f;
            best = j;
          }
        }
      }
      if (best >= 0) return best;
    }
    int best = -1;
    double best_score = opt_.integrality_tolerance;
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (!p_.is_integer[j] || lower(j) >= upper(j)) continue;
      const double f = Fractionality(x(j));
      if (f > best_score) {
        best_score = f;
        best = j;
      }
    }
    return best;
  }

  // The bounds of one child of branching on j at value v: down sets j <= floor(v), up
  // sets j >= floor(v) + 1 and, in a one-of group, the other members to 0. Returns the
  // distance the branching moves j, or a negative value when the child is empty.
  double ChildBounds(int j, double v, bool up, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                     std::vector<BoundChange>* changes) const {
    const double floor_v = std::floor(v + opt_.integrality_tolerance);
    BoundChange ch{j, (*lower)(j), (*upper)(j)};
    if (up) {
      ch.lower = std::max(ch.lower, floor_v + 1.0);
    } else {
      ch.upper = std::min(ch.upper, floor_v);
    }
    if (ch.lower > ch.upper) return -1.0;
    changes->push_back(ch);
    (*lower)(j) = ch.lower;
    (*upper)(j) = ch.upper;
    if (up && group_of_[j] >= 0 && ch.lower >= 1.0) {  // choosing j = 1 rules the others out
      for (int other : p_.sos1_groups[group_of_[j]]) {
        if (other != j && (*upper)(other) > 0.0) {
          changes->push_back({other, (*lower)(other), 0.0});
          (*upper)(other) = 0.0;
          if ((*lower)(other) > 0.0) return -1.0;
        }
      }
    }
    return std::max(up ? floor_v + 1.0 - v : v - floor_v, opt_.integrality_tolerance);
  }

  void Branch(const Node& node, const RelaxationResult& rel, double bound, int j,
              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const std::vector<BoundChange>& fixings) {
    const Eigen::VectorXd& x = rel.x;
    const double floor_v = std::floor(x(j) + opt_.integrality_tolerance);
    Node children[2];  // down, up
    bool valid[2];
    for (int up = 0; up < 2; ++up) {
      Node& child = children[up];
      child.changes = node.changes;
      child.changes.insert(child.changes.end(), fixings.begin(), fixings.end());
      child.parent_bound = bound;
      child.depth = node.depth + 1;
      child.warm_start = x;
      child.branch_var = j;
      child.branch_up = up == 1;
      child.parent_objective = rel.objective;
      Eigen::VectorXd l = lower, u = upper;
      child.branch_distance = ChildBounds(j, x(j), up == 1, &l, &u, &child.changes);
      valid[up] = child.branch_distance > 0.0;
    }
    just_branched_ = valid[0] || valid[1];
    // Pushed last is explored first by a dive: go towards the relaxation's rounding.
    const bool up_first = x(j) - floor_v >= 0.5 || group_of_[j] >= 0;
    const int first = up_first ? 1 : 0;
    if (valid[1 - first]) open_.push_back(std::move(children[1 - first]));
    if (valid[first]) open_.push_back(std::move(children[first]));
  }

  // Reliability branching. Returns the variable, -1 when x is integral, or kPruned when
  // strong branching shows that both children of some candidate are empty or cut off.
  int ChooseByReliability(const RelaxationResult& rel, Eigen::VectorXd* lower, Eigen::VectorXd* upper) {
    const Eigen::VectorXd& x = rel.x;
    struct Candidate {
      int var;
      double down_dist, up_dist, score;
    };
    std::vector<Candidate> candidates;
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (!p_.is_integer[j] || (*lower)(j) >= (*upper)(j)) continue;
      const double f = x(j) - std::floor(x(j));
      if (std::min(f, 1.0 - f) <= opt_.integrality_tolerance) continue;
      const double down = f, up = 1.0 - f;
      candidates.push_back({j, down, up,
                            PseudoCosts::Score(down * pseudo_.PerUnit(j, false), up * pseudo_.PerUnit(j, true))});
    }
    if (candidates.empty()) return -1;
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    int best = candidates.front().var;
    double best_score = -1.0;
    int trials = 0, since_better = 0;
    for (const Candidate& c : candidates) {
      const bool reliable = pseudo_.Count(c.var, false) >= opt_.reliability &&
                            pseudo_.Count(c.var, true) >= opt_.reliability;
      double score = c.score;
      if (!reliable && trials < opt_.strong_branching_candidates &&
          since_better < opt_.strong_branching_lookahead && !Active().Expired()) {
        ++trials;
        double gain[2];
        StrongBranchGains(c.var, x, rel.objective, *lower, *upper, gain);
        if (std::isinf(gain[0]) && std::isinf(gain[1])) return kPruned;
        score = PseudoCosts::Score(std::min(gain[0], kLargeGain), std::min(gain[1], kLargeGain));
      }
      if (score > best_score) {
        best_score = score;
        best = c.var;
        since_better = 0;
      } else {
        ++since_better;
      }
    }
    return best;
  }

  // gain[down, up]: each child's objective increase over its parent (see RecordTrial).
  void StrongBranchGains(int j, const Eigen::VectorXd& x, double parent_objective, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper, double gain[2]) {
    // The two children are solved side by side when there are two workers.
    struct Trial {
      double distance = -1.0;
      bool empty = false;
      RelaxationResult child;
    };
    Trial trials[2];
    const auto solve = [&](int up, RelaxationSolver& solver) {
      Trial& t = trials[up];
      Eigen::VectorXd l = lower, u = upper;
      std::vector<BoundChange> unused;
      t.distance = ChildBounds(j, x(j), up == 1, &l, &u, &unused);
      t.empty = t.distance <= 0.0 || (opt_.bound_propagation && PropagateBounds(p_, &l, &u).infeasible);
      if (!t.empty) t.child = SolveWith(solver, l, u, &x);
    };
    if (solvers_.size() >= 2) {
      ForEachInParallel(2, [&](int up) { solve(up, *solvers_[up]); });
    } else {
      for (int up = 0; up < 2; ++up) solve(up, *solvers_.front());
    }
    for (int up = 0; up < 2; ++up) gain[up] = RecordTrial(j, up == 1, parent_objective, trials[up].distance,
                                                          trials[up].empty, trials[up].child);
  }

  // The objective increase of one strong-branching child over its parent, +inf when the
  // child is empty or cannot beat the incumbent; recorded in the pseudo-costs when solved.
  double RecordTrial(int j, bool up, double parent_objective, double distance, bool empty,
                     const RelaxationResult& child) {
    if (empty) return kInfinity;
    ++result_.strong_branching_solves;
    ++result_.relaxations;
    if (child.status == RelaxationStatus::kInfeasible) return kInfinity;
    if (child.status != RelaxationStatus::kSolved) return distance * pseudo_.PerUnit(j, up);
    const double gain = std::max(0.0, child.objective - parent_objective);
    pseudo_.Record(j, up, gain, distance);
    if (HasIncumbent() && !Improves(child.objective)) {
      NoteGapPrune(child.objective);
      return kInfinity;
    }
    return gain;
  }

  // Fix the integers to a rounding of x and solve the remaining convex QP.
  void TryRounding(const Eigen::VectorXd& x) {
    if (!opt_.rounding_heuristic) return;
    std::vector<Eigen::VectorXd> proposals;
    if (rounding_) proposals = rounding_(x);
    Eigen::VectorXd simple = x;
    for (const auto& group : p_.sos1_groups) {
      int top = group.front();
      for (int j : group) if (x(j) > x(top)) top = j;
      for (int j : group) simple(j) = j == top ? 1.0 : 0.0;
    }
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (p_.is_integer[j] && group_of_[j] < 0) simple(j) = std::round(x(j));
    }
    proposals.push_back(simple);
    // A proposal may already be a plan (a heuristic's own, such as relax-and-fix's): it
    // is kept even when no time is left for its QP.
    for (const Eigen::VectorXd& proposal : proposals) OfferIncumbent(proposal);
    // Each proposal is a QP with the integers fixed: solved a round of workers at a time.
    const int workers = static_cast<int>(solvers_.size());
    for (size_t first = 0; first < proposals.size(); first += workers) {
      if (Active().Expired()) return;
      const int count = static_cast<int>(std::min<size_t>(workers, proposals.size() - first));
      std::vector<RelaxationResult> results(count);
      const RelaxationRequest request = Request(Eigen::VectorXd(), Eigen::VectorXd(), &x);
      ForEachInParallel(count, [&](int k) {
        results[k] = SolveWithIntegersFixed(p_, proposals[first + k], *solvers_[k], request);
      });
      result_.relaxations += count;
      for (RelaxationResult& rel : results) {
        if (rel.status == RelaxationStatus::kSolved) OfferIncumbent(std::move(rel.x));
      }
    }
  }

  void OfferIncumbent(Eigen::VectorXd x) {
    const std::optional<double> objective = FeasibleObjective(p_, &x, opt_.feasibility_tolerance);
    if (!objective) return;
    if (!HasIncumbent() || *objective < result_.objective) {
      result_.x = std::move(x);
      result_.objective = *objective;
      last_improvement_ = Clock::now();
      if (opt_.on_incumbent) ReportProgress();
    }
  }

  // The least bound of everything not yet settled: open nodes, the round in flight,
  // subtrees that could not be bounded and subtrees pruned by the gap tolerance.
  double UnexploredBound() const {
    double bound = std::min({in_flight_bound_, unresolved_bound_, gap_pruned_bound_});
    for (const Node& node : open_) bound = std::min(bound, node.parent_bound);
    return bound;
  }

  static double RelativeGap(double objective, double bound) {
    return (objective - bound) / std::max(1.0, std::abs(objective));
  }

  void ReportProgress() const {
    BranchAndBoundResult progress;
    progress.status = SolveStatus::kFeasible;
    progress.objective = result_.objective;
    progress.bound = std::min(result_.objective, std::max(result_.bound, UnexploredBound()));
    progress.gap = RelativeGap(progress.objective, progress.bound);
    progress.nodes = result_.nodes;
    progress.relaxations = result_.relaxations;
    progress.strong_branching_solves = result_.strong_branching_solves;
    progress.propagation_prunes = result_.propagation_prunes;
    progress.solve_time_s = Elapsed();
    opt_.on_incumbent(progress);
  }

  BranchAndBoundResult Finish() {
    result_.solve_time_s = Elapsed();
    // A relaxation the deadline cut short left its subtree unresolved: that is the time
    // limit, not a solver failure.
    if (Active().Expired() && (root_failed_ || unresolved_bound_ < kInfinity || !open_.empty())) {
      hit_time_limit_ = true;
    }
    const double open_bound = UnexploredBound();
    if (HasIncumbent()) {
      result_.bound = std::min(result_.objective, std::max(result_.bound, open_bound));
      if (open_.empty() && unresolved_bound_ == kInfinity) {
        result_.bound = std::min(result_.objective, gap_pruned_bound_);
      }
      result_.gap = RelativeGap(result_.objective, result_.bound);
      const bool limits = hit_time_limit_ || hit_node_limit_;
      if (!limits && unresolved_bound_ == kInfinity) {
        result_.status = SolveStatus::kOptimal;
      } else if (result_.gap <= opt_.relative_gap && unresolved_bound_ == kInfinity) {
        result_.status = SolveStatus::kOptimal;
      } else {
        result_.status = hit_time_limit_ ? SolveStatus::kTimeLimit : SolveStatus::kFeasible;
      }
    } else if (root_infeasible_ || (open_.empty() && !hit_time_limit_ && !hit_node_limit_ &&
                                    unresolved_bound_ == kInfinity)) {
      result_.status = SolveStatus::kInfeasible;
      result_.bound = kInfinity;
    } else if (root_failed_ && !hit_time_limit_) {
      result_.status = SolveStatus::kInternalError;
    } else {
      result_.status = SolveStatus::kNoSolution;
      result_.bound = std::max(result_.bound, open_bound == kInfinity ? result_.bound : open_bound);
    }
    return result_;
  }

  const Miqp& p_;
  const std::vector<RelaxationSolver*>& solvers_;  // one per worker
  const BranchAndBoundOptions& opt_;
  const RoundingHeuristic& rounding_;
  const Clock::time_point start_;
  Clock::time_point last_improvement_;  // when the incumbent last improved
  const Deadline deadline_;       // time_limit_s from the start, or the caller's deadline if sooner
  const Deadline hard_deadline_;  // the caller's deadline alone under time_limit_needs_incumbent
  PseudoCosts pseudo_;
  std::vector<int> group_of_;
  std::vector<Node> open_;
  BranchAndBoundResult result_;
  bool just_branched_ = false;  // open_.back() is the preferred child of the last node
  bool root_done_ = false;
  bool hit_time_limit_ = false;
  bool hit_node_limit_ = false;
  bool root_infeasible_ = false;
  bool root_failed_ = false;
  double unresolved_bound_ = kInfinity;
  double gap_pruned_bound_ = kInfinity;  // least bound of the subtrees pruned by the gap
  double in_flight_bound_ = kInfinity;   // least parent bound of the round being processed;
                                         // infinity between rounds
};

}  // namespace

BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding) {
  CheckMiqpShape(problem);
  MFP_CHECK_MSG(!solvers.empty(), "branch-and-bound needs at least one relaxation solver");
  for (const RelaxationSolver* s : solvers) MFP_CHECK(s != nullptr);
  Search search(problem, solvers, options, extra_rounding);
  return search.Run();
}

BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, RelaxationSolver& solver,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding) {
  return SolveBranchAndBound(problem, std::vector<RelaxationSolver*>{&solver}, options, extra_rounding);
}

}  // namespace mfp
