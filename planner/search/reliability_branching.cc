#include "planner/search/internal/reliability_branching.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "planner/search/internal/bound_propagation.h"
#include "planner/search/internal/parallel_for.h"

namespace mfp {
namespace {

constexpr double kLargeGain = 1e12;  // stands in for an empty child in a product score

}  // namespace

int ReliabilityBranching::Choose(const RelaxationResult& rel, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper) {
  const Miqp& p = state_.problem();
  const BranchAndBoundOptions& opt = state_.options();
  const Eigen::VectorXd& x = rel.x;
  struct Candidate {
    int var;
    double down_dist, up_dist, score;
  };
  std::vector<Candidate> candidates;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (!p.is_integer[j] || lower(j) >= upper(j)) continue;
    const double f = x(j) - std::floor(x(j));
    if (std::min(f, 1.0 - f) <= opt.integrality_tolerance) continue;
    const double down = f, up = 1.0 - f;
    candidates.push_back({j, down, up, PseudoCosts::Score(down * pseudo_.PerUnit(j, false), up * pseudo_.PerUnit(j, true))});
  }
  if (candidates.empty()) return -1;
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  int best = candidates.front().var;
  double best_score = -1.0;
  int trials = 0, since_better = 0;
  for (const Candidate& c : candidates) {
    const bool reliable =
        pseudo_.Count(c.var, false) >= opt.reliability && pseudo_.Count(c.var, true) >= opt.reliability;
    double score = c.score;
    if (!reliable && trials < opt.strong_branching_candidates && since_better < opt.strong_branching_lookahead &&
        !state_.Active().Expired()) {
      ++trials;
      double gain[2];
      StrongBranchGains(c.var, x, rel.objective, lower, upper, gain);
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

void ReliabilityBranching::StrongBranchGains(int j, const Eigen::VectorXd& x, double parent_objective,
                                             const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                             double gain[2]) {
  // The two children are solved side by side when there are two workers.
  struct Trial {
    double distance = -1.0;
    bool empty = false;
    RelaxationResult child;
  };
  Trial trials[2];
  const bool propagate = state_.options().bound_propagation;
  const auto solve = [&](int up, RelaxationSolver& solver) {
    Trial& t = trials[up];
    Eigen::VectorXd l = lower, u = upper;
    std::vector<BoundChange> unused;
    t.distance = branching_.ChildBounds(j, x(j), up == 1, &l, &u, &unused);
    t.empty = t.distance <= 0.0 || (propagate && PropagateBounds(state_.problem(), &l, &u).infeasible);
    if (!t.empty) t.child = state_.SolveWith(solver, l, u, &x);
  };
  if (state_.workers() >= 2) {
    ForEachInParallel(2, [&](int up) { solve(up, state_.solver(up)); });
  } else {
    for (int up = 0; up < 2; ++up) solve(up, state_.solver(0));
  }
  for (int up = 0; up < 2; ++up) {
    gain[up] = RecordTrial(j, up == 1, parent_objective, trials[up].distance, trials[up].empty, trials[up].child);
  }
}

double ReliabilityBranching::RecordTrial(int j, bool up, double parent_objective, double distance, bool empty,
                                         const RelaxationResult& child) {
  if (empty) return kInfinity;
  BranchAndBoundResult& result = state_.result();
  ++result.strong_branching_solves;
  ++result.relaxations;
  CountFallbacks(child, &result);
  if (child.status == RelaxationStatus::kInfeasible) return kInfinity;
  if (child.status != RelaxationStatus::kSolved) return distance * pseudo_.PerUnit(j, up);
  const double gain = std::max(0.0, child.objective - parent_objective);
  pseudo_.Record(j, up, gain, distance);
  if (state_.HasIncumbent() && !state_.Improves(child.objective)) {
    state_.NoteGapPrune(child.CertifiedFloor());
    return kInfinity;
  }
  return gain;
}

}  // namespace mfp
