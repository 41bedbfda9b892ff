#include "planner/branch_and_bound.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "planner/bound_propagation.h"
#include "planner/check.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

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
  Eigen::VectorXd warm_start;  // parent's relaxation point
};

class Search {
 public:
  Search(const Miqp& problem, RelaxationSolver& solver, const BranchAndBoundOptions& options,
         const RoundingHeuristic& rounding)
      : p_(problem), solver_(solver), opt_(options), rounding_(rounding), start_(Clock::now()) {
    group_of_.assign(p_.num_variables(), -1);
    for (size_t g = 0; g < p_.sos1_groups.size(); ++g) {
      for (int j : p_.sos1_groups[g]) group_of_[j] = static_cast<int>(g);
    }
  }

  BranchAndBoundResult Run() {
    Node root;
    open_.push_back(std::move(root));
    bool root_done = false;
    while (!open_.empty()) {
      if (Elapsed() >= opt_.time_limit_s) {
        hit_time_limit_ = true;
        break;
      }
      if (result_.nodes >= opt_.max_nodes) {
        hit_node_limit_ = true;
        break;
      }
      Node node = PopNode();
      if (HasIncumbent() && !Improves(node.parent_bound)) continue;
      ++result_.nodes;
      Eigen::VectorXd lower = p_.var_lower, upper = p_.var_upper;
      for (const BoundChange& ch : node.changes) {
        lower(ch.index) = ch.lower;
        upper(ch.index) = ch.upper;
      }
      if (opt_.bound_propagation && PropagateBounds(p_, &lower, &upper).infeasible) {
        ++result_.propagation_prunes;
        if (!root_done) root_infeasible_ = true;
        root_done = true;
        continue;
      }
      RelaxationResult rel = SolveRelaxation(lower, upper, node.warm_start.size() ? &node.warm_start : nullptr);
      if (rel.status != RelaxationStatus::kSolved && node.warm_start.size()) {
        rel = SolveRelaxation(lower, upper, nullptr);  // a bad warm start can stall Ipopt
      }
      if (rel.status == RelaxationStatus::kInfeasible) {
        if (!root_done) root_infeasible_ = true;
        root_done = true;
        continue;
      }
      if (rel.status != RelaxationStatus::kSolved) {
        // Cannot bound this subtree: drop it and remember that optimality is unproven.
        unresolved_bound_ = std::min(unresolved_bound_, node.parent_bound);
        if (!root_done) root_failed_ = true;
        root_done = true;
        continue;
      }
      const double bound = std::max(rel.objective, node.parent_bound);
      if (!root_done) {
        root_done = true;
        result_.bound = bound;
        TryRounding(rel.x);
      }
      if (HasIncumbent() && !Improves(bound)) continue;
      const int branch_var = ChooseBranchVariable(rel.x, lower, upper);
      if (branch_var < 0) {
        OfferIncumbent(rel.x);
        continue;
      }
      if (opt_.rounding_heuristic && opt_.rounding_frequency > 0 &&
          result_.nodes % opt_.rounding_frequency == 0) {
        TryRounding(rel.x);
      }
      Branch(node, rel.x, bound, branch_var, lower, upper);
    }
    return Finish();
  }

 private:
  double Elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  bool HasIncumbent() const { return result_.x.size() > 0; }

  // True when a subtree with this bound may still beat the incumbent by more than the gap.
  bool Improves(double bound) const {
    const double tol = std::max(opt_.absolute_gap, opt_.relative_gap * std::max(1.0, std::abs(result_.objective)));
    return bound < result_.objective - tol;
  }

  RelaxationResult SolveRelaxation(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                   const Eigen::VectorXd* warm) {
    solver_.SetTimeLimit(std::max(1e-3, opt_.time_limit_s - Elapsed()));
    ++result_.relaxations;
    return solver_.Solve(p_, lower, upper, warm);
  }

  Node PopNode() {
    size_t pick = open_.size() - 1;  // depth first: newest
    const bool best_bound = opt_.node_selection == NodeSelection::kBestBound ||
                            (opt_.node_selection == NodeSelection::kDiveThenBestBound && HasIncumbent());
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

  void Branch(const Node& node, const Eigen::VectorXd& x, double bound, int j,
              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
    const double floor_v = std::floor(x(j) + opt_.integrality_tolerance);
    Node down, up;
    for (Node* child : {&down, &up}) {
      child->changes = node.changes;
      child->parent_bound = bound;
      child->depth = node.depth + 1;
      child->warm_start = x;
    }
    down.changes.push_back({j, lower(j), std::min(upper(j), floor_v)});
    up.changes.push_back({j, std::max(lower(j), floor_v + 1.0), upper(j)});
    // In a one-of group, choosing j = 1 rules the others out.
    if (group_of_[j] >= 0 && floor_v + 1.0 >= 1.0) {
      for (int other : p_.sos1_groups[group_of_[j]]) {
        if (other != j && upper(other) > 0.0) up.changes.push_back({other, 0.0, 0.0});
      }
    }
    const bool up_valid = up.changes.back().lower <= up.changes.back().upper;
    const bool down_valid = down.changes.back().lower <= down.changes.back().upper;
    // Pushed last is explored first by a dive: go towards the relaxation's rounding.
    const bool up_first = x(j) - floor_v >= 0.5 || group_of_[j] >= 0;
    if (up_first) {
      if (down_valid) open_.push_back(std::move(down));
      if (up_valid) open_.push_back(std::move(up));
    } else {
      if (up_valid) open_.push_back(std::move(up));
      if (down_valid) open_.push_back(std::move(down));
    }
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
    for (const Eigen::VectorXd& r : proposals) {
      if (Elapsed() >= opt_.time_limit_s) return;
      Eigen::VectorXd lower = p_.var_lower, upper = p_.var_upper;
      for (int j = 0; j < p_.num_variables(); ++j) {
        if (!p_.is_integer[j]) continue;
        const double v = std::clamp(std::round(r(j)), p_.var_lower(j), p_.var_upper(j));
        lower(j) = upper(j) = v;
      }
      const RelaxationResult rel = SolveRelaxation(lower, upper, &x);
      if (rel.status == RelaxationStatus::kSolved) OfferIncumbent(rel.x);
    }
  }

  void OfferIncumbent(Eigen::VectorXd x) {
    for (int j = 0; j < p_.num_variables(); ++j) {
      if (p_.is_integer[j]) x(j) = std::round(x(j));
    }
    if (p_.MaxViolation(x) > opt_.feasibility_tolerance) return;
    const double objective = p_.Objective(x);
    if (!HasIncumbent() || objective < result_.objective) {
      result_.x = std::move(x);
      result_.objective = objective;
    }
  }

  BranchAndBoundResult Finish() {
    result_.solve_time_s = Elapsed();
    double open_bound = kInfinity;
    for (const Node& node : open_) open_bound = std::min(open_bound, node.parent_bound);
    open_bound = std::min(open_bound, unresolved_bound_);
    if (HasIncumbent()) {
      result_.bound = std::min(result_.objective, std::max(result_.bound, open_bound));
      if (open_.empty() && unresolved_bound_ == kInfinity) result_.bound = result_.objective;
      result_.gap = (result_.objective - result_.bound) / std::max(1.0, std::abs(result_.objective));
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
    } else if (root_failed_) {
      result_.status = SolveStatus::kInternalError;
    } else {
      result_.status = SolveStatus::kNoSolution;
      result_.bound = std::max(result_.bound, open_bound == kInfinity ? result_.bound : open_bound);
    }
    return result_;
  }

  const Miqp& p_;
  RelaxationSolver& solver_;
  const BranchAndBoundOptions& opt_;
  const RoundingHeuristic& rounding_;
  const Clock::time_point start_;
  std::vector<int> group_of_;
  std::vector<Node> open_;
  BranchAndBoundResult result_;
  bool hit_time_limit_ = false;
  bool hit_node_limit_ = false;
  bool root_infeasible_ = false;
  bool root_failed_ = false;
  double unresolved_bound_ = kInfinity;
};

}  // namespace

BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, RelaxationSolver& solver,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding) {
  CheckMiqpShape(problem);
  Search search(problem, solver, options, extra_rounding);
  return search.Run();
}

}  // namespace mfp
