#pragma once
// Pseudo-costs for branching: per integer variable and direction, the mean increase of
// the relaxation's objective per unit of change of the variable, learnt from every child
// solved (and from strong-branching trials). A direction is "reliable" once it has been
// observed reliability times; unreliable candidates are strong-branched instead.
#include <vector>

namespace mfp {

class PseudoCosts {
 public:
  explicit PseudoCosts(int num_variables)
      : sum_(2, std::vector<double>(num_variables, 0.0)), count_(2, std::vector<int>(num_variables, 0)) {}

  // gain: objective increase of the child over its parent (>= 0); distance: how far the
  // branching moved the variable from its relaxed value (> 0).
  void Record(int var, bool up, double gain, double distance);

  int Count(int var, bool up) const { return count_[up][var]; }
  // Mean gain per unit change; the mean over all observed variables when var has none yet.
  double PerUnit(int var, bool up) const;

  // Product score (as SCIP and others use): favours variables whose both children rise.
  static double Score(double down_gain, double up_gain);

 private:
  std::vector<std::vector<double>> sum_;
  std::vector<std::vector<int>> count_;
  double all_sum_[2] = {0.0, 0.0};
  int all_count_[2] = {0, 0};
};

}  // namespace mfp
