#pragma once
// Bound propagation over the linear rows of a Miqp (feasibility-based bound tightening):
// each row's activity range over the current variable box tightens the bounds of its
// variables, integers rounded inwards, for a few passes. Branch-and-bound runs it at
// every node: an assignment of regions that no foot can satisfy is usually caught here,
// in microseconds, instead of by a relaxation solve.
#include <Eigen/Core>
#include <vector>

#include "planner/miqp/miqp.h"

namespace mfp {

struct PropagationResult {
  bool infeasible = false;  // some row cannot be met, or some bounds crossed
  int tightened = 0;        // number of bound changes made
};

// One row's step of PropagateBounds: tightens the bounds of the row's variables by the
// row's activity range, appending each variable it moved to moved_vars. Returns false when
// the row cannot be met within the bounds.
bool TightenByRow(const Miqp& problem, int row, double tolerance, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                  std::vector<int>* moved_vars);

// Tightens lower/upper in place. max_passes bounds the work; tolerance is the slack
// allowed before a crossing counts as infeasible.
PropagationResult PropagateBounds(const Miqp& problem, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                                  int max_passes = 3, double tolerance = 1e-7);

}  // namespace mfp
