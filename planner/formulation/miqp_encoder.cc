#include "planner/formulation/internal/miqp_encoder.h"

#include "base/check.h"
#include "planner/robot/nominal_foot.h"

namespace mfp {

StepExpr MiqpEncoder::Rotated(int i, const Eigen::Vector2d& offset_body_m, int axis) const {
  MFP_CHECK(i >= e_.num_legs());
  const int cfg = i / e_.num_legs();
  const LinExpr zero;
  return axis == 0 ? NominalFootX(zero, e_.Sin(cfg), e_.Cos(cfg), offset_body_m)
                   : NominalFootY(zero, e_.Sin(cfg), e_.Cos(cfg), offset_body_m);
}

std::pair<double, double> MiqpEncoder::YawBounds(int j) const {
  MFP_CHECK(j >= 0);
  const LinExpr yaw = e_.Yaw(j / e_.num_legs());
  if (j < e_.num_legs() || yaw.terms.empty()) {
    const double fixed = e_.StartStepYaw(j);
    return {fixed, fixed};
  }
  MFP_CHECK(yaw.terms.size() == 1 && yaw.terms[0].second == 1.0);
  return {b_->lower(yaw.terms[0].first), b_->upper(yaw.terms[0].first)};
}

StepExpr MiqpEncoder::Shared(const std::string& name, const StepExpr& expr, double lower, double upper) {
  MFP_CHECK_MSG(expr.rotations.empty(), name + ": the MIQP has no exact rotation");
  MFP_CHECK(lower < upper);
  const int v = b_->AddVariable(name, lower, upper, false);
  b_->AddRow(name + "_def", LinExpr::Var(v) - expr.lin, 0.0, 0.0);
  return StepExpr(LinExpr::Var(v));
}

void MiqpEncoder::AddRow(RowKind /*kind*/, const std::string& name, const StepExpr& expr, double lower,
                         double upper) {
  MFP_CHECK_MSG(expr.rotations.empty(), name + ": the MIQP has no exact rotation");
  b_->AddRow(name, expr.lin, lower, upper);
}

void MiqpEncoder::AddImpliedRow(RowKind /*kind*/, const std::string& name, int indicator, const StepExpr& expr,
                                double upper, double big_m) {
  MFP_CHECK_MSG(expr.rotations.empty(), name + ": the MIQP has no exact rotation");
  if (big_m <= 0.0) return;
  b_->AddRow(name, expr.lin + LinExpr::Var(indicator, big_m), -kInfinity, upper + big_m);
}

}  // namespace mfp
