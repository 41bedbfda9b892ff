#pragma once
// K = L D L' of a symmetric matrix whose pattern is fixed and already in elimination
// order (the interior point's Newton matrix, interior_point_kkt.h), refactorised with new
// values many times. Private to planner/qp.
//
// The arithmetic is Eigen's SimplicialLDLT (up-looking, row by row, NaturalOrdering on an
// upper triangle) operation for operation, so factors and solves are the same to the
// last bit. What differs is where the symbolic work happens: SimplicialLDLT walks the
// elimination tree for every row's pattern at every factorisation; here those patterns
// and each entry's place in L are recorded once, by Analyse, and Factorize only computes.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace mfp {

class SparseLdlt {
 public:
  using Matrix = Eigen::SparseMatrix<double>;  // compressed columns

  // Records the patterns of L for this pattern (upper triangle: column k holds rows <= k,
  // sorted). Values are not read.
  void Analyse(const Matrix& upper);
  // Factorises a matrix with Analyse's pattern; false when a pivot is exactly zero (the
  // factors are then unusable).
  bool Factorize(const Matrix& upper);
  // K^-1 b with the last factors.
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;

  // D of the last factors (its signs: K's inertia).
  Eigen::Map<const Eigen::VectorXd> Pivots() const { return {d_.data(), static_cast<Eigen::Index>(d_.size())}; }
  Eigen::Index FactorNonZeros() const { return static_cast<Eigen::Index>(l_row_.size()); }

 private:
  int n_ = 0;
  std::vector<int> l_start_;      // column j of L: entries [l_start_[j], l_start_[j + 1])
  std::vector<int> l_row_;        // each entry's row
  std::vector<double> l_value_;   // each entry's value
  std::vector<double> d_;         // D
  // Row k of L, in the order the factorisation visits it: column pattern_col_[e] with
  // the entry stored at pattern_slot_[e], for e in [pattern_start_[k], pattern_start_[k + 1]).
  std::vector<int> pattern_start_, pattern_col_, pattern_slot_;
  std::vector<double> y_;         // dense work row of Factorize
};

}  // namespace mfp
