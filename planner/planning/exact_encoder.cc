#include "planner/planning/internal/exact_encoder.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"

namespace mfp {
namespace {

// Whether the coefficients of each variable of expr sum to 0.
bool TermsCancel(const LinExpr& expr) {
  std::vector<std::pair<int, double>> terms = expr.terms;
  std::sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t k = 0; k < terms.size();) {
    double sum = 0.0;
    size_t end = k;
    for (; end < terms.size() && terms[end].first == terms[k].first; ++end) sum += terms[end].second;
    if (sum != 0.0) return false;
    k = end;
  }
  return true;
}

}  // namespace

double ValueAt(const LinExpr& expr, const Eigen::VectorXd& x) {
  double v = expr.constant;
  for (const auto& [var, coef] : expr.terms) v += coef * x(var);
  return v;
}

double ExactRow::Value(const Eigen::VectorXd& x) const {
  double v = ValueAt(lin, x);
  if (has_offset) {
    const double yaw = yaw_var >= 0 ? x(yaw_var) : fixed_yaw;
    const double c = std::cos(yaw), s = std::sin(yaw);
    v -= axis == 0 ? c * offset.x() - s * offset.y() : s * offset.x() + c * offset.y();
  }
  return v;
}

double ExactRow::YawDerivative(const Eigen::VectorXd& x) const {
  const double c = std::cos(x(yaw_var)), s = std::sin(x(yaw_var));
  return axis == 0 ? s * offset.x() + c * offset.y() : -(c * offset.x() - s * offset.y());
}

double ExactRow::Violation(const Eigen::VectorXd& x) const {
  const double v = Value(x);
  return std::max({0.0, v - upper, lower - v});
}

ExactEncoder::ExactEncoder(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x, double margin_m)
    : f_(formulation), miqp_x_(miqp_x), margin_m_(margin_m) {
  const FootstepVariables& v = f_.vars();
  const Miqp& miqp = f_.miqp();
  const int n = f_.num_legs(), N = f_.num_steps(), B = f_.num_configurations();
  trimmed_.assign(N, false);
  for (int i = n; i < N; ++i) trimmed_[i] = miqp_x(v.trim[i]) > 0.5;
  step_var_.assign(N, -1);
  std::vector<double> start, lower, upper;
  auto add_var = [&](int miqp_var) {
    start.push_back(miqp_x(miqp_var));
    lower.push_back(miqp.var_lower(miqp_var));
    upper.push_back(miqp.var_upper(miqp_var));
    return static_cast<int>(start.size()) - 1;
  };
  for (int i = n; i < N; ++i) {
    if (trimmed_[i]) continue;
    step_var_[i] = add_var(v.x[i]);
    add_var(v.y[i]);
    add_var(v.z[i]);
  }
  theta_var_.assign(B, -1);
  for (int cfg = 1; cfg < B; ++cfg) {
    const bool held = f_.options().trimmed_configurations_hold_yaw && trimmed_[cfg * n];
    theta_var_[cfg] = held ? theta_var_[cfg - 1] : add_var(v.theta[cfg]);
  }
  start_ = Eigen::Map<Eigen::VectorXd>(start.data(), static_cast<Eigen::Index>(start.size()));
  lower_ = Eigen::Map<Eigen::VectorXd>(lower.data(), static_cast<Eigen::Index>(lower.size()));
  upper_ = Eigen::Map<Eigen::VectorXd>(upper.data(), static_cast<Eigen::Index>(upper.size()));
}

StepExpr ExactEncoder::Position(int j, int axis) const {
  const FootstepProblem& problem = f_.problem();
  const int n = f_.num_legs();
  while (j >= n && trimmed_[j]) j -= n;
  if (j < 0 && !problem.history_feet_world_m.empty()) return LinExpr::Constant(problem.history_feet_world_m[j + n](axis));
  if (j < n) {
    while (j < 0) j += n;
    return LinExpr::Constant(problem.start_feet_world_m[j](axis));
  }
  return LinExpr::Var(step_var_[j] + axis);
}

StepExpr ExactEncoder::CentreOfContacts(int i, int axis) const {
  const int n = f_.num_legs();
  StepExpr sum;
  for (int j = i - n + 1; j <= i; ++j) sum += (1.0 / n) * Position(j, axis);
  return sum;
}

StepExpr ExactEncoder::NominalFoot(int i, int axis) const {
  const FootstepProblem& problem = f_.problem();
  const int cfg = i / f_.num_legs();
  RotatedOffset rotation;
  rotation.offset_body_m = problem.robot->legs[f_.LegOfStep(i)].nominal_offset_body_m;
  rotation.axis = axis;
  if (cfg == 0) {
    rotation.fixed_yaw_rad = problem.start_step_yaw_rad.empty() ? problem.start_yaw_rad : problem.start_step_yaw_rad[i];
  } else {
    rotation.yaw_var = theta_var_[cfg];
    rotation.fixed_yaw_rad = problem.start_yaw_rad;
  }
  StepExpr out = CentreOfContacts(i, axis);
  out.rotations.push_back(rotation);
  return out;
}

StepExpr ExactEncoder::Rotated(int i, const Eigen::Vector2d& offset_body_m, int axis) const {
  const int cfg = i / f_.num_legs();
  MFP_CHECK(cfg >= 1);
  RotatedOffset rotation;
  rotation.offset_body_m = offset_body_m;
  rotation.axis = axis;
  rotation.yaw_var = theta_var_[cfg];  // < 0: a held yaw of configuration 1, the start yaw
  rotation.fixed_yaw_rad = f_.problem().start_yaw_rad;
  StepExpr out;
  out.rotations.push_back(rotation);
  return out;
}

std::pair<double, double> ExactEncoder::YawBounds(int j) const {
  const FootstepProblem& problem = f_.problem();
  const int cfg = j / f_.num_legs();
  if (cfg == 0) {
    const double fixed = problem.start_step_yaw_rad.empty() ? problem.start_yaw_rad : problem.start_step_yaw_rad[j];
    return {fixed, fixed};
  }
  const int var = theta_var_[cfg];
  if (var < 0) return {problem.start_yaw_rad, problem.start_yaw_rad};
  return {lower_(var), upper_(var)};
}

StepExpr ExactEncoder::Yaw(int cfg) const {
  return theta_var_[cfg] >= 0 ? LinExpr::Var(theta_var_[cfg]) : LinExpr::Constant(f_.problem().start_yaw_rad);
}

void ExactEncoder::AddRow(RowKind kind, const std::string& name, const StepExpr& expr, double lower, double upper) {
  MFP_CHECK_MSG(expr.rotations.size() <= 1 && (expr.rotations.empty() || expr.rotations[0].coefficient == -1.0),
                name + ": the polisher's rows subtract at most one rotated offset");
  ExactRow row;
  row.lin = expr.lin;
  if (!expr.rotations.empty()) {
    const RotatedOffset& r = expr.rotations[0];
    row.has_offset = true;
    row.yaw_var = r.yaw_var;
    row.fixed_yaw = r.fixed_yaw_rad;
    row.offset = r.offset_body_m;
    row.axis = r.axis;
  }
  // A row without a variable is a constant: nothing to solve. So is the yaw change of a
  // configuration that holds the yaw before (its two yaw terms cancel). The height change
  // of a trimmed step is an identity too (0 = 0 after substitution) but stays, as it
  // always has: leaving it out moves the interior point's path, and so the polished
  // plans in their last digits and the next windows' searches.
  const bool has_variable = !row.lin.terms.empty() || (row.has_offset && row.yaw_var >= 0);
  if (!has_variable || (kind == RowKind::kYawChange && TermsCancel(row.lin))) return;
  row.lower = lower;
  row.upper = upper;
  row.tighten = kind == RowKind::kYawChange ? 1e-9 : margin_m_;
  rows_.push_back(std::move(row));
}

void ExactEncoder::AddImpliedRow(RowKind kind, const std::string& name, int indicator, const StepExpr& expr,
                                 double upper, double /*big_m*/) {
  if (miqp_x_(indicator) > 0.5) AddRow(kind, name, expr, -kInfinity, upper);
}

}  // namespace mfp
