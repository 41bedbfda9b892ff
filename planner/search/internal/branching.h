#pragma once
// The branching rules that need no relaxation solve (BranchingRule kMostFractional,
// kSos1Split, kGroupOrder) and the children's bounds that every rule shares: the down
// child sets x_j <= floor(v), the up child x_j >= floor(v) + 1 and, in a one-of group,
// the group's other members to 0.
#include <Eigen/Core>
#include <vector>

#include "planner/miqp/miqp.h"
#include "planner/search/branch_and_bound.h"
#include "planner/search/internal/search_node.h"

namespace mfp {

// A branching choice that proved the node empty (reliability branching's strong trials).
constexpr int kPruned = -2;

class Branching {
 public:
  Branching(const Miqp& problem, const BranchAndBoundOptions& options);

  // The one-of group of variable j, or -1.
  int GroupOf(int j) const { return group_of_[j]; }

  // The integer variable to branch on at relaxation point x within the node's bounds by
  // options.branching (kReliability: as kMostFractional), or -1 when x is integral.
  int ChooseVariable(const Eigen::VectorXd& x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) const;

  // The bounds of one child of branching on j at value v, applied to lower/upper and
  // appended to changes. Returns the distance the branching moves j, or a negative value
  // when the child is empty.
  double ChildBounds(int j, double v, bool up, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                     std::vector<BoundChange>* changes) const;

 private:
  int FirstFractionalGroup(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                           const Eigen::VectorXd& upper) const;
  int MostFractionalGroupMember(const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                                const Eigen::VectorXd& upper) const;
  int MostFractional(const Eigen::VectorXd& x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) const;

  const Miqp& p_;
  const BranchAndBoundOptions& opt_;
  std::vector<int> group_of_;
};

}  // namespace mfp
