#include "planner/miqp/miqp.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"

namespace mfp {

int Miqp::num_integer() const {
  return static_cast<int>(std::count(is_integer.begin(), is_integer.end(), true));
}

double Miqp::Objective(const Eigen::VectorXd& x) const {
  MFP_CHECK(x.size() == num_variables());
  return 0.5 * x.dot(Q * x) + c.dot(x) + constant;
}

double Miqp::MaxViolation(const Eigen::VectorXd& x) const {
  MFP_CHECK(x.size() == num_variables());
  double worst = MaxViolationOfRows(x);
  for (int j = 0; j < num_variables(); ++j) {
    worst = std::max({worst, var_lower(j) - x(j), x(j) - var_upper(j)});
  }
  return worst;
}

double Miqp::MaxViolationOfRows(const Eigen::VectorXd& x) const {
  MFP_CHECK(x.size() == num_variables());
  double worst = 0.0;
  const Eigen::VectorXd ax = A * x;
  for (int i = 0; i < num_rows(); ++i) worst = std::max({worst, row_lower(i) - ax(i), ax(i) - row_upper(i)});
  return worst;
}

double Miqp::MaxIntegrality(const Eigen::VectorXd& x) const {
  double worst = 0.0;
  for (int j = 0; j < num_variables(); ++j) {
    if (is_integer[j]) worst = std::max(worst, std::abs(x(j) - std::round(x(j))));
  }
  return worst;
}

void CheckMiqpShape(const Miqp& p) {
  const int n = p.num_variables();
  MFP_CHECK(p.Q.rows() == n && p.Q.cols() == n);
  MFP_CHECK(p.A.cols() == n);
  MFP_CHECK(p.row_lower.size() == p.A.rows() && p.row_upper.size() == p.A.rows());
  MFP_CHECK(p.var_lower.size() == n && p.var_upper.size() == n);
  MFP_CHECK(static_cast<int>(p.is_integer.size()) == n);
  MFP_CHECK(static_cast<int>(p.var_names.size()) == n);
  MFP_CHECK(static_cast<int>(p.row_names.size()) == p.A.rows());
  const Eigen::SparseMatrix<double> diff = p.Q - Eigen::SparseMatrix<double>(p.Q.transpose());
  MFP_CHECK_MSG(diff.norm() <= 1e-9 * (1.0 + p.Q.norm()), "Q must be symmetric");
  for (const auto& group : p.sos1_groups) {
    for (int j : group) MFP_CHECK(j >= 0 && j < n && p.is_integer[j]);
  }
}

}  // namespace mfp
