#include "planner/formulation/internal/step_expressions.h"

#include <cmath>

#include "planner/formulation/centre_of_contacts.h"
#include "planner/robot/nominal_foot.h"

namespace mfp {

int LegOfStep(const FootstepProblem& problem, int step) {
  const int n = problem.robot->num_legs();
  const int phase = ((problem.gait_phase + step) % n + n) % n;
  return problem.robot->gait[phase];
}

std::string StepName(const char* what, int i) { return std::string(what) + "_" + std::to_string(i); }

std::vector<int> AddExactlyOneBinaries(const char* binary_prefix, const char* row_name, int i, int count,
                                       MiqpBuilder* b) {
  std::vector<int> binaries;
  binaries.reserve(count);
  LinExpr sum;
  for (int k = 0; k < count; ++k) {
    binaries.push_back(b->AddBinary(StepName(binary_prefix, i) + "_" + std::to_string(k)));
    sum += LinExpr::Var(binaries.back());
  }
  b->AddRow(StepName(row_name, i), sum, 1.0, 1.0);
  return binaries;
}

StepExpressions::StepExpressions(const FootstepProblem& problem, const FootstepVariables& vars)
    : problem_(problem), vars_(vars), n_(problem.robot->num_legs()) {}

LinExpr StepExpressions::Position(int j, int axis) const {
  if (j < 0 && !problem_.history_feet_world_m.empty()) {
    return LinExpr::Constant(problem_.history_feet_world_m[j + n_](axis));
  }
  while (j < 0) j += n_;
  if (j < n_) return LinExpr::Constant(problem_.start_feet_world_m[j](axis));
  const int index = axis == 0 ? vars_.x[j] : axis == 1 ? vars_.y[j] : vars_.z[j];
  return LinExpr::Var(index);
}

LinExpr StepExpressions::CentreOfContactsSum(int i, int axis) const {
  return mfp::CentreOfContacts<LinExpr>(i, n_, [&](int j) { return Position(j, axis); });
}

LinExpr StepExpressions::CentreOfContacts(int i, int axis) const {
  return i >= n_ ? LinExpr::Var(axis == 0 ? vars_.px[i] : vars_.py[i]) : CentreOfContactsSum(i, axis);
}

LinExpr StepExpressions::Yaw(int cfg) const {
  return cfg == 0 ? LinExpr::Constant(problem_.start_yaw_rad) : LinExpr::Var(vars_.theta[cfg]);
}

LinExpr StepExpressions::Sin(int cfg) const {
  return cfg == 0 ? LinExpr::Constant(std::sin(problem_.start_yaw_rad)) : LinExpr::Var(vars_.s[cfg]);
}

LinExpr StepExpressions::Cos(int cfg) const {
  return cfg == 0 ? LinExpr::Constant(std::cos(problem_.start_yaw_rad)) : LinExpr::Var(vars_.c[cfg]);
}

double StepExpressions::StartStepYaw(int i) const {
  return problem_.start_step_yaw_rad.empty() || i < 0 || i >= n_ ? problem_.start_yaw_rad : problem_.start_step_yaw_rad[i];
}

LinExpr StepExpressions::NominalFoot(int i, int axis) const {
  const int cfg = i < 0 ? 0 : i / n_;
  const Eigen::Vector2d o = problem_.robot->legs[mfp::LegOfStep(problem_, i)].nominal_offset_body_m;
  const LinExpr p = CentreOfContacts(i, axis);
  if (cfg == 0 && !problem_.start_step_yaw_rad.empty()) {
    // The rotated offset is a constant: R(yaw) o about the origin, then added to p.
    const double yaw = problem_.start_step_yaw_rad[i];
    const double c = std::cos(yaw), s = std::sin(yaw);
    const double offset = axis == 0 ? NominalFootX(0.0, s, c, o) : NominalFootY(0.0, s, c, o);
    return p + LinExpr::Constant(offset);
  }
  return axis == 0 ? NominalFootX(p, Sin(cfg), Cos(cfg), o) : NominalFootY(p, Sin(cfg), Cos(cfg), o);
}

}  // namespace mfp
