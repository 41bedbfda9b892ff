#include "planner/planning/internal/window_program.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "planner/formulation/body_region_faces.h"
#include "planner/formulation/region_faces.h"
#include "planner/formulation/step_limits.h"
#include "planner/formulation/workspace_box.h"
#include "planner/formulation/yaw_change_limit.h"

namespace mfp {

WindowProgram::WindowProgram(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x, double margin_m)
    : f_(formulation), miqp_x_(miqp_x), encoder_(formulation, miqp_x, margin_m) {
  const FootstepProblem& problem = f_.problem();
  const int n = f_.num_legs(), N = f_.num_steps();
  // The box only sizes the MIQP's big-M constants; the polisher's variables keep their
  // MIQP bounds (the same box).
  const Box3 box = MakeWorkspaceBox(problem.regions, problem.start_feet_world_m);
  for (int i = n; i < N; ++i) {
    AddStepLimits(encoder_, *problem.robot, i);
    if (!encoder_.trimmed(i)) {  // a trimmed step stands on its leg's previous foot, already in its region
      const int r = ChosenRegion(i);
      AddRegionFaces(encoder_, problem.regions[r], i, f_.vars().region[i][r], box);
    }
  }
  for (int cfg = 1; cfg < f_.num_configurations(); ++cfg) AddYawChangeLimit(encoder_, *problem.robot, cfg);
  AddChosenBodyRegions(box);
  const std::vector<ExactRow>& rows = encoder_.rows();
  for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
    if (std::isfinite(rows[r].upper)) sides_.emplace_back(r, true);
    if (std::isfinite(rows[r].lower)) sides_.emplace_back(r, false);
  }
  const FootstepVariables& v = f_.vars();
  for (int i = n; i < N; ++i) {
    const int xs[3] = {v.x[i], v.y[i], v.z[i]};
    for (int axis = 0; axis < 3; ++axis) full_map_.emplace_back(xs[axis], encoder_.Position(i, axis).lin);
    full_map_.emplace_back(v.px[i], encoder_.CentreOfContacts(i, 0).lin);
    full_map_.emplace_back(v.py[i], encoder_.CentreOfContacts(i, 1).lin);
  }
}

void WindowProgram::AddChosenBodyRegions(const Box3& box) {
  const FootstepProblem& problem = f_.problem();
  const std::vector<std::vector<int>>& body_region = f_.vars().body_region;
  const int n = f_.num_legs();
  for (int cfg = 1; cfg < static_cast<int>(body_region.size()); ++cfg) {
    for (int r = 0; r < static_cast<int>(body_region[cfg].size()); ++r) {
      const int g = body_region[cfg][r];
      if (miqp_x_(g) < 0.5) continue;
      for (int i = cfg * n; i < std::min(f_.num_steps(), (cfg + 1) * n); ++i) {
        // Exact rotation: no chord error.
        AddBodyRegionFaces(encoder_, problem.robot->body, problem.body_regions[r], r, i, g, 0.0,
                           f_.options().body_margin_m, box);
      }
    }
  }
}

void WindowProgram::SelectNear(const Eigen::VectorXd& x, double slack) {
  std::vector<bool> in(sides_.size(), false);
  for (int k : selected_) in[k] = true;
  for (int k = 0; k < static_cast<int>(sides_.size()); ++k) {
    if (!in[k] && SideValue(x, k) > -slack) selected_.push_back(k);
  }
  std::sort(selected_.begin(), selected_.end());
}

Eigen::VectorXd WindowProgram::FullPoint(const Eigen::VectorXd& x) const {
  Eigen::VectorXd full = miqp_x_;
  for (const auto& [index, expr] : full_map_) full(index) = ValueAt(expr, x);
  const FootstepVariables& v = f_.vars();
  for (int blk = 1; blk < f_.num_configurations(); ++blk) {
    const double t = Yaw(x, blk);
    full(v.theta[blk]) = t;
    full(v.s[blk]) = std::sin(t);
    full(v.c[blk]) = std::cos(t);
  }
  return full;
}

double WindowProgram::Objective(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const {
  const Miqp& miqp = f_.miqp();
  const Eigen::VectorXd full = FullPoint(x);
  if (grad != nullptr) {
    const Eigen::VectorXd g = miqp.Q * full + miqp.c;
    grad->setZero(x.size());
    for (const auto& [index, expr] : full_map_) {
      for (const auto& [var, coef] : expr.terms) (*grad)(var) += coef * g(index);
    }
    const FootstepVariables& v = f_.vars();
    for (int blk = 1; blk < f_.num_configurations(); ++blk) {
      if (encoder_.yaw_var(blk) < 0) continue;
      const double t = x(encoder_.yaw_var(blk));
      (*grad)(encoder_.yaw_var(blk)) += g(v.theta[blk]) + std::cos(t) * g(v.s[blk]) - std::sin(t) * g(v.c[blk]);
    }
  }
  return miqp.Objective(full);
}

void WindowProgram::Inequalities(const Eigen::VectorXd& x, Eigen::VectorXd* values, Eigen::MatrixXd* jacobian) const {
  const int m = num_inequalities();
  values->resize(m);
  if (jacobian != nullptr) jacobian->setZero(m, x.size());
  for (int k = 0; k < m; ++k) {
    const int side = selected_[k];
    (*values)(k) = SideValue(x, side);
    if (jacobian == nullptr) continue;
    const ExactRow& row = encoder_.rows()[sides_[side].first];
    const double sign = sides_[side].second ? 1.0 : -1.0;
    for (const auto& [var, coef] : row.lin.terms) (*jacobian)(k, var) += sign * coef;
    if (row.has_offset && row.yaw_var >= 0) (*jacobian)(k, row.yaw_var) += sign * row.YawDerivative(x);
  }
}

double WindowProgram::MaxViolation(const Eigen::VectorXd& x) const {
  double worst = 0.0;
  for (const ExactRow& row : encoder_.rows()) worst = std::max(worst, row.Violation(x));
  for (int j = 0; j < x.size(); ++j) worst = std::max({worst, lower()(j) - x(j), x(j) - upper()(j)});
  return worst;
}

void WindowProgram::QuadraticModel(const Eigen::VectorXd& xk, Eigen::SparseMatrix<double>* Q, Eigen::VectorXd* c,
                    double* constant) const {
  const Miqp& miqp = f_.miqp();
  const FootstepVariables& v = f_.vars();
  // full(x) = M x + m0 around xk.
  Eigen::VectorXd m0 = miqp_x_;
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& [index, expr] : full_map_) {
    m0(index) = expr.constant;
    for (const auto& [var, coef] : expr.terms) triplets.emplace_back(index, var, coef);
  }
  for (int blk = 1; blk < f_.num_configurations(); ++blk) {
    const int var = encoder_.yaw_var(blk);
    const double t = Yaw(xk, blk), sn = std::sin(t), cs = std::cos(t);
    if (var < 0) {
      m0(v.theta[blk]) = t;
      m0(v.s[blk]) = sn;
      m0(v.c[blk]) = cs;
      continue;
    }
    m0(v.theta[blk]) = 0.0;
    triplets.emplace_back(v.theta[blk], var, 1.0);
    m0(v.s[blk]) = sn - cs * t;
    triplets.emplace_back(v.s[blk], var, cs);
    m0(v.c[blk]) = cs + sn * t;
    triplets.emplace_back(v.c[blk], var, -sn);
  }
  Eigen::SparseMatrix<double> M(miqp.num_variables(), xk.size());
  M.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SparseMatrix<double> QM = miqp.Q * M;
  Eigen::SparseMatrix<double> reduced = Eigen::SparseMatrix<double>(M.transpose()) * QM;
  *Q = 0.5 * (reduced + Eigen::SparseMatrix<double>(reduced.transpose()));
  const Eigen::VectorXd Qm0 = miqp.Q * m0;
  *c = M.transpose() * (Qm0 + miqp.c);
  *constant = 0.5 * m0.dot(Qm0) + miqp.c.dot(m0) + miqp.constant;
}

void WindowProgram::LinearisedSides(const Eigen::VectorXd& xk, Eigen::SparseMatrix<double, Eigen::RowMajor>* J,
                     Eigen::VectorXd* upper) const {
  const int m = num_inequalities();
  std::vector<Eigen::Triplet<double>> triplets;
  upper->resize(m);
  for (int k = 0; k < m; ++k) {
    const int side = selected_[k];
    const ExactRow& row = encoder_.rows()[sides_[side].first];
    const double sign = sides_[side].second ? 1.0 : -1.0;
    double jx = 0.0;
    for (const auto& [var, coef] : row.lin.terms) {
      triplets.emplace_back(k, var, sign * coef);
      jx += sign * coef * xk(var);
    }
    if (row.has_offset && row.yaw_var >= 0) {
      const double d = sign * row.YawDerivative(xk);
      triplets.emplace_back(k, row.yaw_var, d);
      jx += d * xk(row.yaw_var);
    }
    (*upper)(k) = jx - SideValue(xk, side);
  }
  J->resize(m, xk.size());
  J->setFromTriplets(triplets.begin(), triplets.end());  // sums repeated (row, var) terms
}

std::vector<int> WindowProgram::YawVariables() const {
  std::vector<int> out;
  for (int cfg = 0; cfg < f_.num_configurations(); ++cfg) {
    const int var = encoder_.yaw_var(cfg);
    if (var >= 0 && (out.empty() || out.back() != var)) out.push_back(var);
  }
  return out;
}

std::vector<Footstep> WindowProgram::Footsteps(const Eigen::VectorXd& x) const {
  std::vector<Footstep> steps = f_.ExtractFootsteps(miqp_x_);
  for (int i = f_.num_legs(); i < f_.num_steps(); ++i) {
    for (int axis = 0; axis < 3; ++axis) steps[i].position_world_m(axis) = ValueAt(encoder_.Position(i, axis).lin, x);
    steps[i].yaw_rad = Yaw(x, i / f_.num_legs());
  }
  return steps;
}


double WindowProgram::SideValue(const Eigen::VectorXd& x, int side) const {
  const ExactRow& row = encoder_.rows()[sides_[side].first];
  return sides_[side].second ? row.Value(x) - (row.upper - row.tighten) : (row.lower + row.tighten) - row.Value(x);
}

double WindowProgram::Yaw(const Eigen::VectorXd& x, int cfg) const {
  return encoder_.yaw_var(cfg) >= 0 ? x(encoder_.yaw_var(cfg)) : f_.problem().start_yaw_rad;
}

int WindowProgram::ChosenRegion(int i) const {
  int best = -1;
  for (size_t r = 0; r < f_.problem().regions.size(); ++r) {
    const int h = f_.vars().region[i][r];
    if (h >= 0 && (best < 0 || miqp_x_(h) > miqp_x_(f_.vars().region[i][best]))) best = static_cast<int>(r);
  }
  MFP_CHECK(best >= 0);
  return best;
}

}  // namespace mfp
