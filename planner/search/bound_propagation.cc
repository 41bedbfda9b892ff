#include "planner/search/internal/bound_propagation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/check.h"

namespace mfp {
namespace {

// Sum of finite contributions plus a count of infinite ones, so that the activity of
// "the row without variable j" can be formed without re-summing.
struct Activity {
  double finite = 0.0;
  int infinite = 0;
  void Add(double v) {
    if (std::isinf(v)) {
      ++infinite;
    } else {
      finite += v;
    }
  }
  // Activity without one contribution v; infinite when another infinite term remains.
  double Without(double v, double inf_value) const {
    if (std::isinf(v)) return infinite > 1 ? inf_value : finite;
    return infinite > 0 ? inf_value : finite - v;
  }
};

}  // namespace

bool TightenByRow(const Miqp& p, int row, double tolerance, Eigen::VectorXd* lower_ptr, Eigen::VectorXd* upper_ptr,
                  std::vector<int>* moved_vars) {
  Eigen::VectorXd& lower = *lower_ptr;
  Eigen::VectorXd& upper = *upper_ptr;
  constexpr double kTinyCoefficient = 1e-9;
  // A change smaller than this (relative to the variable's range) is not worth a pass.
  constexpr double kMinChange = 1e-6;
  const double lo = p.row_lower(row), hi = p.row_upper(row);
  Activity amin, amax;
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, row); it; ++it) {
    const double a = it.value(), l = lower(it.col()), u = upper(it.col());
    amin.Add(a > 0 ? a * l : a * u);
    amax.Add(a > 0 ? a * u : a * l);
  }
  const double min_all = amin.infinite ? -kInfinity : amin.finite;
  const double max_all = amax.infinite ? kInfinity : amax.finite;
  if (min_all > hi + tolerance * (1.0 + std::abs(hi)) || max_all < lo - tolerance * (1.0 + std::abs(lo))) {
    return false;
  }
  // A row the bounds already keep tightens nothing: each variable's implied bounds
  // lie outside its own (most big-M rows of regions a node has ruled out).
  if (min_all >= lo && max_all <= hi) return true;
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, row); it; ++it) {
    const int j = static_cast<int>(it.col());
    const double a = it.value(), l = lower(j), u = upper(j);
    // A coefficient this small bounds nothing: dividing by it turns rounding noise
    // of the activity into a bound at infinity, a false infeasibility.
    if (l == u || std::abs(a) < kTinyCoefficient) continue;
    const double own_min = a > 0 ? a * l : a * u;
    const double own_max = a > 0 ? a * u : a * l;
    const double rest_min = amin.Without(own_min, -kInfinity);
    const double rest_max = amax.Without(own_max, kInfinity);
    // lo - rest_max <= a x_j <= hi - rest_min
    double new_l = l, new_u = u;
    if (a > 0) {
      if (std::isfinite(hi) && std::isfinite(rest_min)) new_u = std::min(new_u, (hi - rest_min) / a);
      if (std::isfinite(lo) && std::isfinite(rest_max)) new_l = std::max(new_l, (lo - rest_max) / a);
    } else {
      if (std::isfinite(hi) && std::isfinite(rest_min)) new_l = std::max(new_l, (hi - rest_min) / a);
      if (std::isfinite(lo) && std::isfinite(rest_max)) new_u = std::min(new_u, (lo - rest_max) / a);
    }
    if (p.is_integer[j]) {
      new_l = std::ceil(new_l - 1e-6);
      new_u = std::floor(new_u + 1e-6);
    } else {
      // A derived bound is only as exact as the activity sums behind it: kept a
      // tolerance outward, so that rounding cannot cut off a point that meets the rows
      // exactly (a foot standing on its region's edge, held there by a trimmed step).
      new_l -= tolerance * (1.0 + std::abs(new_l));
      new_u += tolerance * (1.0 + std::abs(new_u));
    }
    const double range = std::isfinite(u - l) ? u - l : 1.0;
    if (new_l > new_u) {
      if (new_l > new_u + tolerance * (1.0 + std::abs(new_u))) return false;
      new_l = new_u = 0.5 * (new_l + new_u);  // numerically equal: fix at the midpoint
    }
    bool moved = false;
    if (new_l > l + kMinChange * range) {
      lower(j) = new_l;
      moved = true;
    }
    if (new_u < u - kMinChange * range) {
      upper(j) = new_u;
      moved = true;
    }
    if (moved) {
      moved_vars->push_back(j);
      // Keep this row's activity in step with the new bounds.
      amin = Activity();
      amax = Activity();
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator jt(p.A, row); jt; ++jt) {
        const double b = jt.value(), bl = lower(jt.col()), bu = upper(jt.col());
        amin.Add(b > 0 ? b * bl : b * bu);
        amax.Add(b > 0 ? b * bu : b * bl);
      }
    }
  }
  return true;
}

PropagationResult PropagateBounds(const Miqp& p, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                                  int max_passes, double tolerance) {
  MFP_CHECK(lower->size() == p.num_variables() && upper->size() == p.num_variables());
  PropagationResult result;
  std::vector<int> moved;
  for (int pass = 0; pass < max_passes; ++pass) {
    bool changed = false;
    for (int row = 0; row < p.A.outerSize(); ++row) {
      moved.clear();
      if (!TightenByRow(p, row, tolerance, lower, upper, &moved)) {
        result.infeasible = true;
        return result;
      }
      result.tightened += static_cast<int>(moved.size());
      changed = changed || !moved.empty();
    }
    if (!changed) break;
  }
  return result;
}

}  // namespace mfp
