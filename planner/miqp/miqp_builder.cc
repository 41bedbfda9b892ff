#include "planner/miqp/miqp_builder.h"

#include <cmath>

#include "base/check.h"

namespace mfp {

LinExpr LinExpr::Constant(double value) {
  LinExpr e;
  e.constant = value;
  return e;
}

LinExpr LinExpr::Var(int index, double coefficient) {
  LinExpr e;
  e.terms.emplace_back(index, coefficient);
  return e;
}

LinExpr& LinExpr::operator+=(const LinExpr& other) {
  terms.insert(terms.end(), other.terms.begin(), other.terms.end());
  constant += other.constant;
  return *this;
}

LinExpr& LinExpr::operator-=(const LinExpr& other) {
  for (const auto& [index, coefficient] : other.terms) terms.emplace_back(index, -coefficient);
  constant -= other.constant;
  return *this;
}

LinExpr& LinExpr::operator*=(double scale) {
  for (auto& term : terms) term.second *= scale;
  constant *= scale;
  return *this;
}


int MiqpBuilder::AddVariable(const std::string& name, double lower, double upper, bool integer) {
  MFP_CHECK_MSG(!std::isnan(lower) && !std::isnan(upper) && lower <= upper, name);
  var_names_.push_back(name);
  lower_.push_back(lower);
  upper_.push_back(upper);
  integer_.push_back(integer);
  return static_cast<int>(lower_.size()) - 1;
}

void MiqpBuilder::SetBounds(int index, double lower, double upper) {
  MFP_CHECK(index >= 0 && index < num_variables() && lower <= upper);
  lower_[index] = lower;
  upper_[index] = upper;
}

void MiqpBuilder::AddRow(const std::string& name, const LinExpr& expr, double lower,
                         double upper) {
  MFP_CHECK_MSG(!std::isnan(lower) && !std::isnan(upper) && std::isfinite(expr.constant), name);
  const int row = static_cast<int>(row_names_.size());
  row_names_.push_back(name);
  row_lower_.push_back(lower - expr.constant);
  row_upper_.push_back(upper - expr.constant);
  for (const auto& [index, coefficient] : expr.terms) {
    MFP_CHECK(index >= 0 && index < num_variables() && std::isfinite(coefficient));
    a_triplets_.emplace_back(row, index, coefficient);
  }
}

void MiqpBuilder::AddSquaredCost(const LinExpr& expr, double weight) {
  MFP_CHECK(std::isfinite(weight) && weight >= 0.0);
  // weight (a'x + k)^2 = 0.5 x' (2 weight a a') x + 2 weight k a'x + weight k^2
  for (const auto& [i, ai] : expr.terms) {
    for (const auto& [j, aj] : expr.terms) q_triplets_.emplace_back(i, j, 2.0 * weight * ai * aj);
    linear_cost_.emplace_back(i, 2.0 * weight * expr.constant * ai);
  }
  constant_cost_ += weight * expr.constant * expr.constant;
}

void MiqpBuilder::AddLinearCost(const LinExpr& expr) {
  linear_cost_.insert(linear_cost_.end(), expr.terms.begin(), expr.terms.end());
  constant_cost_ += expr.constant;
}

void MiqpBuilder::AddSos1Group(const std::vector<int>& members) { sos1_.push_back(members); }

Miqp MiqpBuilder::Build() const {
  const int n = num_variables();
  const int m = static_cast<int>(row_names_.size());
  Miqp p;
  p.Q.resize(n, n);
  p.Q.setFromTriplets(q_triplets_.begin(), q_triplets_.end());
  p.Q.prune(0.0);
  p.c = Eigen::VectorXd::Zero(n);
  for (const auto& [index, value] : linear_cost_) p.c(index) += value;
  p.constant = constant_cost_;
  p.A.resize(m, n);
  p.A.setFromTriplets(a_triplets_.begin(), a_triplets_.end());
  p.A.prune(0.0);
  p.row_lower = Eigen::Map<const Eigen::VectorXd>(row_lower_.data(), m);
  p.row_upper = Eigen::Map<const Eigen::VectorXd>(row_upper_.data(), m);
  p.var_lower = Eigen::Map<const Eigen::VectorXd>(lower_.data(), n);
  p.var_upper = Eigen::Map<const Eigen::VectorXd>(upper_.data(), n);
  p.is_integer = integer_;
  p.var_names = var_names_;
  p.row_names = row_names_;
  p.sos1_groups = sos1_;
  CheckMiqpShape(p);
  return p;
}

}  // namespace mfp
