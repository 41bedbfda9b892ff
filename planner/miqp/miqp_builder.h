#pragma once
// Incremental construction of a Miqp from named variables, linear rows and squared
// costs. Used by the footstep formulation and by tests that write small MIQPs by hand.
#include <Eigen/SparseCore>
#include <string>
#include <utility>
#include <vector>

#include "base/expression_arithmetic.h"
#include "planner/miqp/miqp.h"

namespace mfp {

// sum_j coefficient_j * x_j + constant. Terms may repeat a variable; they add up.
// a + b, a - b and scale * a come from ExpressionArithmetic.
struct LinExpr : ExpressionArithmetic<LinExpr> {
  std::vector<std::pair<int, double>> terms;
  double constant = 0.0;

  static LinExpr Constant(double value);
  static LinExpr Var(int index, double coefficient = 1.0);
  LinExpr& operator+=(const LinExpr& other);
  LinExpr& operator-=(const LinExpr& other);
  LinExpr& operator*=(double scale);
};

class MiqpBuilder {
 public:
  int AddVariable(const std::string& name, double lower, double upper, bool integer);
  int AddBinary(const std::string& name) { return AddVariable(name, 0.0, 1.0, true); }
  // lower <= expr <= upper; the expression's constant is moved to the bounds.
  void AddRow(const std::string& name, const LinExpr& expr, double lower, double upper);
  // weight * expr^2 added to the objective.
  void AddSquaredCost(const LinExpr& expr, double weight);
  // expr added to the objective.
  void AddLinearCost(const LinExpr& expr);
  void AddSos1Group(const std::vector<int>& members);
  void SetBounds(int index, double lower, double upper);

  int num_variables() const { return static_cast<int>(lower_.size()); }
  int num_rows() const { return static_cast<int>(row_names_.size()); }
  double lower(int index) const { return lower_[index]; }
  double upper(int index) const { return upper_[index]; }

  Miqp Build() const;

 private:
  std::vector<std::string> var_names_;
  std::vector<double> lower_, upper_;
  std::vector<bool> integer_;
  std::vector<std::string> row_names_;
  std::vector<double> row_lower_, row_upper_;
  std::vector<Eigen::Triplet<double>> a_triplets_;
  std::vector<Eigen::Triplet<double>> q_triplets_;
  std::vector<std::pair<int, double>> linear_cost_;
  double constant_cost_ = 0.0;
  std::vector<std::vector<int>> sos1_;
};

}  // namespace mfp
