#include "planner/search/internal/pseudo_costs.h"

#include <algorithm>

#include "base/check.h"

namespace mfp {

void PseudoCosts::Record(int var, bool up, double gain, double distance) {
  MFP_CHECK(distance > 0.0);
  const double per_unit = std::max(0.0, gain) / distance;
  sum_[up][var] += per_unit;
  ++count_[up][var];
  all_sum_[up] += per_unit;
  ++all_count_[up];
}

double PseudoCosts::PerUnit(int var, bool up) const {
  if (count_[up][var] > 0) return sum_[up][var] / count_[up][var];
  return all_count_[up] > 0 ? all_sum_[up] / all_count_[up] : 1.0;
}

double PseudoCosts::Score(double down_gain, double up_gain) {
  constexpr double kFloor = 1e-6;  // so that one flat side does not zero the product
  return std::max(down_gain, kFloor) * std::max(up_gain, kFloor);
}

}  // namespace mfp
