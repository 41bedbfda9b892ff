#pragma once
// The subtrees a search settled at certified floors below what its gap asks, kept for
// re-certification (BranchAndBoundOptions::recertify_leaves). An interior point's floor
// may lag its objective by more than the gap, so a tree exhausted by the objectives can
// fall short of a proof by its floors alone; a few exact solves of the lowest-floor
// subtrees can close it. At most `capacity` subtrees are kept, those of the lowest
// floors; the others (and the subtrees settled without a box) count by their least floor.
#include <Eigen/Core>
#include <vector>

#include "planner/miqp/miqp.h"

namespace mfp {

struct SettledSubtree {
  double floor = -kInfinity;      // the subtree's bound as claimed so far
  Eigen::VectorXd lower, upper;   // its box
  Eigen::VectorXd relaxed;        // a relaxation point of it or its parent: a warm start (empty: none)
  bool propagated = false;        // lower/upper were propagated over the rows already
  int depth = 0;                  // its node's depth in the tree
  bool recertified = false;       // solved again once (a second solve would certify the same)
};

class LaggingFloors {
 public:
  explicit LaggingFloors(int capacity) : capacity_(capacity) {}

  // Whether a subtree settled at `floor` would be kept, given the floor a proof needs now
  // (`target`: it only falls as the incumbent improves, so a floor at or above it never
  // limits the gap).
  bool Keeps(double floor, double target) const;
  // A settled subtree: kept when Keeps says so (the highest kept one then leaves, if the
  // store is full), otherwise counted by its floor alone.
  void Note(SettledSubtree subtree, double target);
  // A settled subtree without a box: counted by its floor alone.
  void NoteFloor(double floor);

  std::vector<SettledSubtree>& kept() { return kept_; }
  // The least floor of the subtrees not kept.
  double rest_floor() const { return rest_floor_; }
  // The least floor of every subtree noted.
  double Least() const;

 private:
  int capacity_;
  std::vector<SettledSubtree> kept_;
  double rest_floor_ = kInfinity;
};

}  // namespace mfp
