#pragma once
// A mixed-integer quadratic program in plain sparse form, independent of any solver:
//   minimise 0.5 x'Qx + c'x + constant
//   subject to row_lower <= A x <= row_upper,  var_lower <= x <= var_upper,
//              x_j integer for is_integer[j].
// Infinite bounds are +-infinity. Names are kept for MPS export and debugging.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <limits>
#include <string>
#include <vector>

namespace mfp {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Miqp {
  Eigen::SparseMatrix<double> Q;  // symmetric, both triangles stored
  Eigen::VectorXd c;
  double constant = 0.0;
  Eigen::SparseMatrix<double, Eigen::RowMajor> A;
  Eigen::VectorXd row_lower;
  Eigen::VectorXd row_upper;
  Eigen::VectorXd var_lower;
  Eigen::VectorXd var_upper;
  std::vector<bool> is_integer;
  std::vector<std::string> var_names;
  std::vector<std::string> row_names;
  // Groups of binaries constrained to sum to exactly one (region choice per step,
  // yaw segment per configuration): branched on as SOS1 sets.
  std::vector<std::vector<int>> sos1_groups;

  int num_variables() const { return static_cast<int>(c.size()); }
  int num_rows() const { return static_cast<int>(A.rows()); }
  int num_integer() const;

  double Objective(const Eigen::VectorXd& x) const;  // includes constant
  // Largest violation of rows and variable bounds (0 when feasible).
  double MaxViolation(const Eigen::VectorXd& x) const;
  // Largest violation of the rows alone.
  double MaxViolationOfRows(const Eigen::VectorXd& x) const;
  // Largest distance of an integer variable from the nearest integer.
  double MaxIntegrality(const Eigen::VectorXd& x) const;
};

// Aborts (programmer error) when sizes disagree or Q is not square and symmetric.
void CheckMiqpShape(const Miqp& problem);

}  // namespace mfp
