#include "planner/search/internal/branching.h"

#include <algorithm>
#include <cmath>

namespace mfp {
namespace {

double Fractionality(double v) { return std::abs(v - std::round(v)); }

}  // namespace

Branching::Branching(const Miqp& problem, const BranchAndBoundOptions& options) : p_(problem), opt_(options) {
  group_of_.assign(p_.num_variables(), -1);
  for (size_t g = 0; g < p_.sos1_groups.size(); ++g) {
    for (int j : p_.sos1_groups[g]) group_of_[j] = static_cast<int>(g);
  }
}

int Branching::ChooseVariable(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper) const {
  if (opt_.branching == BranchingRule::kGroupOrder) {
    const int j = FirstFractionalGroup(x, lower, upper);
    if (j >= 0) return j;
  }
  if (opt_.branching == BranchingRule::kSos1Split) {
    const int j = MostFractionalGroupMember(x, lower, upper);
    if (j >= 0) return j;
  }
  return MostFractional(x, lower, upper);
}

// kGroupOrder: the first one-of group with a fractional member, in the order the model
// lists them (along the plan); its most fractional member.
int Branching::FirstFractionalGroup(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                                    const Eigen::VectorXd& upper) const {
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
  return -1;
}

// kSos1Split: the group with the most fractional member; branch on that member (its up
// child fixes the whole group).
int Branching::MostFractionalGroupMember(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                                         const Eigen::VectorXd& upper) const {
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
  return best;
}

int Branching::MostFractional(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper) const {
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

double Branching::ChildBounds(int j, double v, bool up, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
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

}  // namespace mfp
