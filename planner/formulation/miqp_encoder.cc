#include "planner/formulation/internal/miqp_encoder.h"

#include "base/check.h"

namespace mfp {

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
