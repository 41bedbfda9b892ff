#pragma once
// The encoder the constraint families write their rows through (as ifopt's constraint
// sets fill their own rows over variables another object owns). A family states its
// rows once, in the quantities of the seed paper; each encoder decides what those
// quantities are and where the rows go:
//   MiqpEncoder (miqp_encoder.h)                  the MIQP: positions and centres of
//        contacts as variables, R(yaw) through the sin/cos chord variables; rows into a
//        MiqpBuilder, an implied row as a big-M row on its binary.
//   ExactEncoder (planner/planning/internal/exact_encoder.h) the polisher: the MIQP's integers
//        fixed (a trimmed step is its leg's previous foot, a configuration that holds its
//        yaw has the one before), R(yaw) with exact sin and cos of a yaw variable.
//   the plan validator (planner/planning/plan_validation.cc): every quantity a value of
//        the plan's footsteps; a row is its excess over its bounds.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "base/expression_arithmetic.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

// What a row limits: the polisher's margin and the validator's report depend on it.
enum class RowKind {
  kReferenceBox,   // |f_i - r_nom,i|_inf <= l_bnd, per axis [m]
  kReachability,   // |f_i - r_nom,i-n|_inf <= d_lim, per axis [m]
  kHeightChange,   // |z_i - z_i-n| <= dz_max [m]
  kYawChange,      // |theta_b - theta_b-1| <= max_yaw_change [rad]
  kRegionFace,     // a_k . f_i <= b_k of the step's region [m]
  kBodyRegion,     // a_k . (p_i + R(theta_b(i)) k) <= b_k for a body corner k [m]
};
constexpr int kNumRowKinds = 6;

// An offset turned by the exact rotation of a yaw: coefficient (R(yaw) o)_axis. yaw_var
// indexes the encoder's own variables; yaw_var < 0: the yaw is the constant fixed_yaw_rad.
// Only an encoder with exact trigonometry makes these (the MIQP's are chord variables).
struct RotatedOffset {
  double coefficient = 1.0;
  Eigen::Vector2d offset_body_m = Eigen::Vector2d::Zero();
  int axis = 0;  // 0 x, 1 y
  int yaw_var = -1;
  double fixed_yaw_rad = 0.0;
};

// A linear expression over the encoder's variables plus exact rotated offsets.
struct StepExpr : ExpressionArithmetic<StepExpr> {
  LinExpr lin;
  std::vector<RotatedOffset> rotations;

  StepExpr() = default;
  StepExpr(LinExpr linear) : lin(std::move(linear)) {}  // NOLINT: a linear expression is a StepExpr
  StepExpr& operator+=(const StepExpr& other);
  StepExpr& operator-=(const StepExpr& other);
  StepExpr& operator*=(double scale);
};

// `expr` with its rotated offsets folded into one, on axis x with coefficient -1, when
// they all turn by the same yaw: sum_k c_k (R o_k)_axis_k = -(R o')_x with
// o' = -sum_k c_k A_k o_k, A_x = I and A_y = R(-pi/2), since (R o)_y = (R R(-pi/2) o)_x.
// (A row along a diagonal of a nominal foot, which the polisher takes with one offset.)
// Otherwise `expr` unchanged.
StepExpr FoldRotations(StepExpr expr);

class StepEncoder {
 public:
  virtual ~StepEncoder() = default;

  virtual int num_legs() const = 0;
  // The leg step j moves.
  virtual int LegOfStep(int j) const = 0;
  // Position of step j on one axis (0 x, 1 y, 2 z); steps before the plan (j < n) are
  // constants (the start stance, or the history before it for j < 0).
  virtual StepExpr Position(int j, int axis) const = 0;
  // p_i, the centre of contacts of the n latest footsteps ending at step i (eq. 2), axis 0 or 1.
  virtual StepExpr CentreOfContacts(int i, int axis) const = 0;
  // r_nom,i = p_i + R(theta_b(i)) o_leg(i) on axis 0 or 1 (eq. 3).
  virtual StepExpr NominalFoot(int i, int axis) const = 0;
  // theta_b, the yaw of configuration cfg (cfg 0: the start yaw).
  virtual StepExpr Yaw(int cfg) const = 0;
  // R(theta_b(i)) o on axis 0 or 1: a body-frame offset turned by the yaw of new step i's
  // configuration (i >= n).
  virtual StepExpr Rotated(int i, const Eigen::Vector2d& offset_body_m, int axis) const = 0;
  // [lowest, highest] yaw the configuration of step j (j >= 0) may take [rad]: the MIQP's
  // and the polisher's bounds on its yaw variable, the start's yaw for the start's steps,
  // and, for the validator, the yaw step j reports (both ends). Rows that must hold at
  // every yaw of that range (the footprint polygon's) are written for it.
  virtual std::pair<double, double> YawBounds(int j) const = 0;

  // `expr` as one quantity that many rows will be written on. The MIQP makes it a
  // variable bounded by [lower, upper], tied to expr by an equality row, so that each of
  // those rows touches that variable instead of expr's terms: the same feasible set (the
  // caller guarantees that the rows it writes on it imply lower <= expr <= upper) with
  // sparser rows, hence cheaper node QPs. The other encoders return expr itself.
  virtual StepExpr Shared(const std::string& /*name*/, const StepExpr& expr, double /*lower*/, double /*upper*/) {
    return expr;
  }

  // lower <= expr <= upper. name: the MIQP's row name.
  virtual void AddRow(RowKind kind, const std::string& name, const StepExpr& expr, double lower, double upper) = 0;
  // indicator => expr <= upper, with indicator a binary of the MIQP and big_m a bound on
  // expr - upper over the variables' box (big_m <= 0: the box implies the row).
  virtual void AddImpliedRow(RowKind kind, const std::string& name, int indicator, const StepExpr& expr, double upper,
                             double big_m) = 0;
};

}  // namespace mfp
