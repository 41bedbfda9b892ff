// The interior point's LDL' against Eigen's SimplicialLDLT, whose arithmetic it repeats:
// the same factors and solves to the last bit, on one pattern refactorised many times;
// and the Newton matrices it factorises (KktAssembly) against Eigen's sparse products.
#include "planner/qp/internal/sparse_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <random>
#include <vector>

#include "base/deadline.h"
#include "planner/qp/internal/interior_point_kkt.h"

namespace mfp {
namespace {

using Matrix = SparseLdlt::Matrix;

// The upper triangle of Q + G' diag(w) G + diag(b) in a fixed pattern (Q a chain, G with
// a few entries per row), with weights spread over as many decades as an interior
// point's late iterations give them.
struct RandomNewtonMatrices {
  explicit RandomNewtonMatrices(int n, int rows, unsigned seed) : n(n), rng(seed) {
    std::uniform_int_distribution<int> column(0, n - 1);
    std::normal_distribution<double> normal;
    for (int r = 0; r < rows; ++r) {
      for (int e = 0; e < 3; ++e) g.emplace_back(r, column(rng), normal(rng));
    }
    G.resize(rows, n);
    G.setFromTriplets(g.begin(), g.end());
  }

  Matrix Next() {
    std::uniform_real_distribution<double> decade(-8.0, 12.0);
    Eigen::VectorXd w(G.rows()), b(n);
    for (Eigen::Index r = 0; r < w.size(); ++r) w(r) = std::pow(10.0, decade(rng));
    for (int j = 0; j < n; ++j) b(j) = std::pow(10.0, decade(rng));
    Matrix Q(n, n);
    std::vector<Eigen::Triplet<double>> q;
    for (int j = 0; j + 1 < n; ++j) {
      q.emplace_back(j, j, 2.0);
      q.emplace_back(j + 1, j + 1, 2.0);
      q.emplace_back(j, j + 1, -2.0);
      q.emplace_back(j + 1, j, -2.0);
    }
    Q.setFromTriplets(q.begin(), q.end());
    Matrix K = Q + Matrix(G.transpose() * w.asDiagonal() * G);
    K.diagonal() += b;
    Matrix upper = K.triangularView<Eigen::Upper>();
    // Every step keeps one pattern: K's structural entries, whatever the values.
    for (int k = 0; k < upper.outerSize(); ++k) {
      for (Matrix::InnerIterator it(upper, k); it; ++it) {
        if (it.value() == 0.0) it.valueRef() = 1e-300;
      }
    }
    upper.makeCompressed();
    return upper;
  }

  int n;
  std::mt19937 rng;
  std::vector<Eigen::Triplet<double>> g;
  Matrix G;
};

TEST(SparseLdlt, FactorsAndSolvesExactlyAsSimplicialLdltOnEveryRefactorisation) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    RandomNewtonMatrices matrices(120, 300, seed);
    Matrix first = matrices.Next();
    SparseLdlt ours;
    ours.Analyse(first);
    Eigen::SimplicialLDLT<Matrix, Eigen::Upper, Eigen::NaturalOrdering<int>> eigen;
    eigen.analyzePattern(first);
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal;
    for (int step = 0; step < 5; ++step) {
      const Matrix K = step == 0 ? first : matrices.Next();
      ASSERT_TRUE(ours.Factorize(K));
      eigen.factorize(K);
      ASSERT_EQ(eigen.info(), Eigen::Success);
      EXPECT_EQ(ours.FactorNonZeros(), eigen.matrixL().nestedExpression().nonZeros());
      Eigen::VectorXd b(K.cols());
      for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = normal(rng);
      const Eigen::VectorXd x = ours.Solve(b), expected = eigen.solve(b);
      for (Eigen::Index i = 0; i < b.size(); ++i) ASSERT_EQ(x(i), expected(i)) << "seed " << seed << " step " << step;
      // and it is a solution: K x = b to the factorisation's accuracy
      const Eigen::VectorXd residual = b - K.selfadjointView<Eigen::Upper>() * x;
      const double scale = K.cwiseAbs().toDense().maxCoeff() * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
      EXPECT_LT(residual.lpNorm<Eigen::Infinity>(), 1e-6 * scale);
    }
  }
}

// A footstep MIQP's shape: `steps` blocks of `per_step` variables, a chain cost between
// consecutive steps, and rows coupling a step with itself and with the step before (the
// reachability and region rows), its Newton matrices in the interior point's own minimum
// degree order (KktAssembly).
InequalityForm BandedByStep(int steps, int per_step, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> within(0, per_step - 1);
  InequalityForm f;
  f.n = steps * per_step;
  std::vector<Eigen::Triplet<double>> g, q;
  int rows = 0;
  for (int s = 0; s < steps; ++s) {
    for (int r = 0; r < 3 * per_step; ++r, ++rows) {
      const int from = r % 2 == 0 && s > 0 ? s - 1 : s;
      for (int e = 0; e < 4; ++e) g.emplace_back(rows, (e % 2 == 0 ? from : s) * per_step + within(rng), normal(rng));
    }
    for (int j = 0; j < per_step && s > 0; ++j) {
      const int a = (s - 1) * per_step + j, b = s * per_step + j;
      q.emplace_back(a, a, 1.0);
      q.emplace_back(b, b, 1.0);
      q.emplace_back(a, b, -1.0);
      q.emplace_back(b, a, -1.0);
    }
  }
  f.elastic = rows;
  f.G.resize(rows, f.n);
  f.G.setFromTriplets(g.begin(), g.end());
  f.Gt = f.G.transpose();
  f.Q.resize(f.n, f.n);
  f.Q.setFromTriplets(q.begin(), q.end());
  f.q = Eigen::VectorXd::Zero(f.n + rows);
  f.d = Eigen::VectorXd::Zero(2 * rows + 2 * f.n);
  return f;
}

TEST(SparseLdlt, SimplicialLdltsPivotsAndSolvesOnMinimumDegreeOrderedNewtonMatrices) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const InequalityForm f = BandedByStep(24, 8, seed);
    const KktAssembly assembly(f, Deadline());
    ASSERT_FALSE(assembly.interrupted);
    SpMat K = assembly.pattern;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> decade(-8.0, 12.0);
    std::normal_distribution<double> normal;
    SparseLdlt ours;
    Eigen::SimplicialLDLT<Matrix, Eigen::Upper, Eigen::NaturalOrdering<int>> eigen;
    for (int step = 0; step < 4; ++step) {
      Eigen::VectorXd row_weight(f.elastic), bound_weight(f.n);
      for (Eigen::Index r = 0; r < row_weight.size(); ++r) row_weight(r) = std::pow(10.0, decade(rng));
      for (Eigen::Index j = 0; j < bound_weight.size(); ++j) bound_weight(j) = std::pow(10.0, decade(rng));
      assembly.Assemble(row_weight, bound_weight, &K);
      if (step == 0) {
        ours.Analyse(K);
        eigen.analyzePattern(K);
      }
      ASSERT_TRUE(ours.Factorize(K));
      eigen.factorize(K);
      ASSERT_EQ(eigen.info(), Eigen::Success);
      ASSERT_EQ(ours.FactorNonZeros(), eigen.matrixL().nestedExpression().nonZeros());
      // the same pivots (so the same inertia) and the same solutions, to the last bit
      const Eigen::VectorXd d = eigen.vectorD();
      Eigen::VectorXd b(K.cols());
      for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = normal(rng);
      const Eigen::VectorXd x = ours.Solve(b), expected = eigen.solve(b);
      for (Eigen::Index i = 0; i < b.size(); ++i) {
        ASSERT_EQ(ours.Pivots()(i), d(i));
        ASSERT_GT(d(i), 0.0);  // K is positive definite
        ASSERT_EQ(x(i), expected(i)) << "seed " << seed << " step " << step << " entry " << i;
      }
    }
  }
}

TEST(KktAssembly, NewtonMatricesAreQPlusGtWGPlusBInThePermutedPattern) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const InequalityForm f = BandedByStep(12, 6, seed);
    const KktAssembly assembly(f, Deadline());
    ASSERT_FALSE(assembly.interrupted);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> decade(-8.0, 12.0);
    Eigen::VectorXd row_weight(f.elastic), bound_weight(f.n);
    for (Eigen::Index r = 0; r < row_weight.size(); ++r) row_weight(r) = std::pow(10.0, decade(rng));
    for (Eigen::Index j = 0; j < bound_weight.size(); ++j) bound_weight(j) = std::pow(10.0, decade(rng));
    SpMat K = assembly.pattern;
    assembly.Assemble(row_weight, bound_weight, &K);
    const Eigen::MatrixXd ours = Eigen::MatrixXd(K).selfadjointView<Eigen::Upper>();
    Eigen::MatrixXd expected = Eigen::MatrixXd(f.Q) + Eigen::MatrixXd(f.Gt * row_weight.asDiagonal() * f.G);
    expected.diagonal() += bound_weight;
    for (int a = 0; a < f.n; ++a) {
      for (int b = 0; b < f.n; ++b) {
        const double scale = std::abs(expected(a, b)) + std::sqrt(std::abs(expected(a, a) * expected(b, b)));
        ASSERT_NEAR(ours(assembly.position[a], assembly.position[b]), expected(a, b), 1e-13 * scale)
            << "seed " << seed << " (" << a << ", " << b << ")";
      }
    }
  }
}

TEST(SparseLdlt, AZeroPivotIsReportedNotDividedBy) {
  // [[1, 1], [1, 1]]: the second pivot is 1 - 1 = 0.
  Matrix K(2, 2);
  K.insert(0, 0) = 1.0;
  K.insert(0, 1) = 1.0;
  K.insert(1, 1) = 1.0;
  K.makeCompressed();
  SparseLdlt ldlt;
  ldlt.Analyse(K);
  EXPECT_FALSE(ldlt.Factorize(K));
  K.coeffRef(1, 1) = 3.0;  // [[1, 1], [1, 3]]: pivots 1 and 2
  ASSERT_TRUE(ldlt.Factorize(K));
  const Eigen::VectorXd x = ldlt.Solve(Eigen::Vector2d(1.0, 1.0));
  EXPECT_DOUBLE_EQ(x(0), 1.0);
  EXPECT_DOUBLE_EQ(x(1), 0.0);
}

}  // namespace
}  // namespace mfp
