#pragma once
// The MIQP's encoder (step_encoder.h): the quantities of StepExpressions (positions and
// centres of contacts as variables, R(yaw) through the sin/cos chord variables), rows
// into a MiqpBuilder, an implied row as a big-M row on its binary.
#include <string>

#include "planner/formulation/internal/step_expressions.h"
#include "planner/formulation/step_encoder.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

class MiqpEncoder final : public StepEncoder {
 public:
  // Both must outlive this object.
  MiqpEncoder(const StepExpressions& expressions, MiqpBuilder* builder) : e_(expressions), b_(builder) {}

  int num_legs() const override { return e_.num_legs(); }
  int LegOfStep(int j) const override { return e_.LegOfStep(j); }
  StepExpr Position(int j, int axis) const override { return e_.Position(j, axis); }
  StepExpr CentreOfContacts(int i, int axis) const override { return e_.CentreOfContacts(i, axis); }
  StepExpr NominalFoot(int i, int axis) const override { return e_.NominalFoot(i, axis); }
  StepExpr Yaw(int cfg) const override { return e_.Yaw(cfg); }
  StepExpr Rotated(int i, const Eigen::Vector2d& offset_body_m, int axis) const override;
  std::pair<double, double> YawBounds(int j) const override;
  // A continuous variable `name` in [lower, upper] and the row variable - expr = 0.
  StepExpr Shared(const std::string& name, const StepExpr& expr, double lower, double upper) override;

  void AddRow(RowKind kind, const std::string& name, const StepExpr& expr, double lower, double upper) override;
  // expr + big_m indicator <= upper + big_m; left out when big_m <= 0.
  void AddImpliedRow(RowKind kind, const std::string& name, int indicator, const StepExpr& expr, double upper,
                     double big_m) override;

 private:
  const StepExpressions& e_;
  MiqpBuilder* b_;
};

}  // namespace mfp
