#pragma once
// The polisher's program for one window: the constraint families written through the
// ExactEncoder (the MIQP point's integers fixed, exact sin/cos) and the MIQP's own cost
// evaluated on the full MIQP point the polisher's variables stand for. Its rows are
// evaluated for NLopt (values and a dense Jacobian) or linearised for the sequential QP
// (sparse rows), each finite side of a row one inequality, optionally only those near
// their bound (SelectNear).
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <utility>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"
#include "planner/formulation/workspace_box.h"
#include "planner/planning/internal/exact_encoder.h"

namespace mfp {

class WindowProgram {
 public:
  // The rows in this order: per new step its limits (ref x, reach x, ref y, reach y, dz)
  // and, when it is not trimmed, the faces of the region the MIQP point chose; then the
  // yaw change of each configuration that turns.
  WindowProgram(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x, double margin_m);

  const Eigen::VectorXd& start() const { return encoder_.start(); }
  const Eigen::VectorXd& lower() const { return encoder_.lower(); }
  const Eigen::VectorXd& upper() const { return encoder_.upper(); }
  int num_inequalities() const { return static_cast<int>(selected_.size()); }

  // Adds to the inequalities the solver sees those within `slack` of their bound at x.
  // Far ones (the opposite sides of the boxes, most region faces) cannot become active
  // in the small moves of a polish, and SLSQP's time per iteration grows with their
  // number; MaxViolation still checks every one.
  void SelectNear(const Eigen::VectorXd& x, double slack);
  void ClearSelection() { selected_.clear(); }

  // The MIQP point x stands for: positions, centres of contacts, yaw and its sin and cos
  // follow x; the rest stays at the MIQP's values.
  Eigen::VectorXd FullPoint(const Eigen::VectorXd& x) const;
  // The MIQP's objective at FullPoint(x); grad (may be null) its gradient in x.
  double Objective(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const;
  // Each selected finite side of a row as one inequality: value - (upper - tighten) <= 0
  // or (lower + tighten) - value <= 0. jacobian may be null.
  void Inequalities(const Eigen::VectorXd& x, Eigen::VectorXd* values, Eigen::MatrixXd* jacobian) const;
  // Largest violation of the untightened constraints and the variable bounds.
  double MaxViolation(const Eigen::VectorXd& x) const;
  // The cost as a quadratic in x, with the sin and cos of each yaw linearised at xk
  // (the formulation's cost weighs theta, not s and c, so this is the exact cost; the
  // linearisation keeps it right should a cost on s or c appear). 0.5 x'Qx + c'x + constant.
  void QuadraticModel(const Eigen::VectorXd& xk, Eigen::SparseMatrix<double>* Q, Eigen::VectorXd* c,
                      double* constant) const;
  // The selected sides linearised at xk as sparse rows: J x <= J xk - g(xk).
  void LinearisedSides(const Eigen::VectorXd& xk, Eigen::SparseMatrix<double, Eigen::RowMajor>* J,
                       Eigen::VectorXd* upper) const;
  // The yaw variables (each configuration's that is not held or fixed), once each.
  std::vector<int> YawVariables() const;
  // As MiqpFormulation::ExtractFootsteps, with the positions and yaws of x.
  std::vector<Footstep> Footsteps(const Eigen::VectorXd& x) const;

 private:
  double SideValue(const Eigen::VectorXd& x, int side) const;
  // Yaw of configuration cfg >= 1.
  double Yaw(const Eigen::VectorXd& x, int cfg) const;
  // The region the MIQP point chose for step i (its largest binary).
  int ChosenRegion(int i) const;
  // The body rows (body_region_faces.h) of the body region each configuration's MIQP
  // point chose, with the exact rotation.
  void AddChosenBodyRegions(const Box3& box);

  const MiqpFormulation& f_;
  const Eigen::VectorXd& miqp_x_;
  ExactEncoder encoder_;
  std::vector<std::pair<int, bool>> sides_;  // (row, upper side?) of each inequality
  std::vector<int> selected_;                // the sides the solver sees (SelectNear)
  std::vector<std::pair<int, LinExpr>> full_map_;
};

}  // namespace mfp
