#pragma once
// The polisher's encoder (planner/formulation/step_encoder.h): the constraint families
// written with the MIQP solution's integers fixed and exact trigonometry.
//   variables    (x, y, z) of each untrimmed new step, then the yaw of each configuration
//                that turns (start, lower and upper bounds from the MIQP point and its
//                variable bounds)
//   trimming     by substitution: a trimmed step is its leg's previous foot, and with
//                trimmed_configurations_hold_yaw a configuration whose first step is
//                trimmed has the yaw of the one before. Trimming's and holding's rows are
//                identities then: the polisher does not write them, and the yaw change
//                of a held configuration is left out (AddRow).
//   rotations    R(yaw) o with exact sin and cos of the yaw variable (a constant yaw for
//                the start configuration)
//   implied rows a row whose indicator binary is 1 at the MIQP point; the others are
//                left out
// Rows are two-sided, each side tightened by margin_m (yaw rows by 1e-9 rad) in the solve.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/step_encoder.h"

namespace mfp {

// lower <= lin(x) - (R(yaw) o)_axis <= upper (has_offset false: no rotation term).
struct ExactRow {
  LinExpr lin;
  bool has_offset = false;
  int yaw_var = -1;          // < 0: the yaw is the constant fixed_yaw
  double fixed_yaw = 0.0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  int axis = 0;
  double lower = 0.0, upper = 0.0;
  double tighten = 0.0;  // lower + tighten <= value <= upper - tighten in the solve

  double Value(const Eigen::VectorXd& x) const;
  // d value / d yaw (only with has_offset and yaw_var >= 0).
  double YawDerivative(const Eigen::VectorXd& x) const;
  double Violation(const Eigen::VectorXd& x) const;
};

// c + sum coef * x[var], the terms in their order.
double ValueAt(const LinExpr& expr, const Eigen::VectorXd& x);

class ExactEncoder final : public StepEncoder {
 public:
  // formulation and miqp_x (a solution of formulation.miqp(), integers integral) must
  // outlive this object.
  ExactEncoder(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x, double margin_m);

  int num_legs() const override { return f_.num_legs(); }
  int LegOfStep(int j) const override { return f_.LegOfStep(j); }
  // Before the window: the history (or the start stance when there is none), as in the
  // formulation; a trimmed step is its leg's previous foot.
  StepExpr Position(int j, int axis) const override;
  // The mean of the positions (no variable of its own).
  StepExpr CentreOfContacts(int i, int axis) const override;
  StepExpr NominalFoot(int i, int axis) const override;
  StepExpr Yaw(int cfg) const override;
  // The yaw variable's bounds (the MIQP's), or the constant yaw of a start step or a held one.
  std::pair<double, double> YawBounds(int j) const override;
  StepExpr Rotated(int i, const Eigen::Vector2d& offset_body_m, int axis) const override;
  void AddRow(RowKind kind, const std::string& name, const StepExpr& expr, double lower, double upper) override;
  void AddImpliedRow(RowKind kind, const std::string& name, int indicator, const StepExpr& expr, double upper,
                     double big_m) override;

  bool trimmed(int step) const { return trimmed_[step]; }
  // The polisher's variable of configuration cfg's yaw; < 0: the start yaw.
  int yaw_var(int cfg) const { return theta_var_[cfg]; }
  const Eigen::VectorXd& start() const { return start_; }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }
  const std::vector<ExactRow>& rows() const { return rows_; }

 private:
  const MiqpFormulation& f_;
  const Eigen::VectorXd& miqp_x_;
  double margin_m_;
  std::vector<bool> trimmed_;
  std::vector<int> step_var_, theta_var_;
  Eigen::VectorXd start_, lower_, upper_;
  std::vector<ExactRow> rows_;
};

}  // namespace mfp
