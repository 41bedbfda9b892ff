#include "planner/qp/internal/sparse_ldlt.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "base/check.h"

namespace mfp {

void SparseLdlt::Analyse(const Matrix& upper) {
  MFP_CHECK(upper.rows() == upper.cols() && upper.isCompressed());
  n_ = static_cast<int>(upper.cols());
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  // 1. The elimination tree and L's column counts: row k of L holds every node on the
  //    tree paths from K's entries (i, k), i < k, up to k.
  std::vector<int> parent(n_, -1), count(n_, 0), tags(n_, -1);
  for (int k = 0; k < n_; ++k) {
    tags[k] = k;
    for (int e = outer[k]; e < outer[k + 1]; ++e) {
      for (int i = inner[e]; i < k && tags[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        ++count[i];
        tags[i] = k;
      }
    }
  }
  // L's entries counted in 64 bits: more than an int holds is a problem no budget admitted.
  int64_t entries = 0;
  for (int j = 0; j < n_; ++j) entries += count[j];
  MFP_CHECK(entries <= std::numeric_limits<int>::max());
  l_start_.assign(n_ + 1, 0);
  for (int j = 0; j < n_; ++j) l_start_[j + 1] = l_start_[j] + count[j];
  l_row_.assign(l_start_[n_], 0);
  l_value_.assign(l_start_[n_], 0.0);
  d_.assign(n_, 0.0);
  // 2. Each row's pattern in the order the up-looking factorisation visits it (each
  //    path pushed whole onto a stack, so a column comes after those it updates), and
  //    where each entry lands in its column.
  pattern_start_.assign(1, 0);
  pattern_col_.clear();
  pattern_slot_.clear();
  std::vector<int> filled(n_, 0), stack(n_), path(n_);
  std::fill(tags.begin(), tags.end(), -1);
  for (int k = 0; k < n_; ++k) {
    int top = n_;
    tags[k] = k;
    for (int e = outer[k]; e < outer[k + 1]; ++e) {
      int i = inner[e];
      if (i > k) continue;
      int length = 0;
      for (; tags[i] != k; i = parent[i]) {
        path[length++] = i;
        tags[i] = k;
      }
      while (length > 0) stack[--top] = path[--length];
    }
    for (; top < n_; ++top) {
      const int i = stack[top];
      const int slot = l_start_[i] + filled[i]++;
      l_row_[slot] = k;
      pattern_col_.push_back(i);
      pattern_slot_.push_back(slot);
    }
    pattern_start_.push_back(static_cast<int>(pattern_col_.size()));
  }
}

bool SparseLdlt::Factorize(const Matrix& upper) {
  MFP_CHECK(upper.cols() == n_ && static_cast<int>(pattern_start_.size()) == n_ + 1);
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  const double* value = upper.valuePtr();
  y_.assign(n_, 0.0);
  for (int k = 0; k < n_; ++k) {
    for (int e = outer[k]; e < outer[k + 1]; ++e) {
      if (inner[e] <= k) y_[inner[e]] += value[e];
    }
    // Row k of L by a sparse triangular solve against the columns before it.
    double d = y_[k] * 1.0 + 0.0;  // SimplicialLDLT's shift function at its defaults
    y_[k] = 0.0;
    for (int e = pattern_start_[k]; e < pattern_start_[k + 1]; ++e) {
      const int i = pattern_col_[e], slot = pattern_slot_[e];
      const double yi = y_[i];
      y_[i] = 0.0;
      const double l_ki = yi / d_[i];
      for (int p = l_start_[i]; p < slot; ++p) y_[l_row_[p]] -= l_value_[p] * yi;
      d -= l_ki * yi;
      l_value_[slot] = l_ki;
    }
    d_[k] = d;
    if (!(std::isfinite(d) && d != 0.0)) return false;  // a zero or non-finite pivot: no factor
  }
  return true;
}

Eigen::VectorXd SparseLdlt::Solve(const Eigen::VectorXd& b) const {
  MFP_CHECK(b.size() == n_);
  Eigen::VectorXd x = b;
  for (int i = 0; i < n_; ++i) {  // L y = b, L unit lower triangular, by columns
    const double xi = x(i);
    if (xi == 0.0) continue;
    for (int p = l_start_[i]; p < l_start_[i + 1]; ++p) x(l_row_[p]) -= xi * l_value_[p];
  }
  for (int i = 0; i < n_; ++i) x(i) = (1.0 / d_[i]) * x(i);
  for (int i = n_ - 1; i >= 0; --i) {  // L' x = z, by rows of L'
    double xi = x(i);
    for (int p = l_start_[i]; p < l_start_[i + 1]; ++p) xi -= l_value_[p] * x(l_row_[p]);
    x(i) = xi;
  }
  return x;
}

}  // namespace mfp
