#include "planner/planning/window_polisher.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

#include <Eigen/Sparse>

#include "planner/base/check.h"
#include "planner/qp/interior_point_qp.h"
#include "planner/qp/nonlinear_program.h"

namespace mfp {
namespace {

// c + sum coef * x[var] over the polisher's variables.
struct Affine {
  double constant = 0.0;
  std::vector<std::pair<int, double>> terms;
  void Add(const Affine& other, double scale) {
    constant += scale * other.constant;
    for (const auto& [var, coef] : other.terms) terms.emplace_back(var, scale * coef);
  }
  double At(const Eigen::VectorXd& x) const {
    double v = constant;
    for (const auto& [var, coef] : terms) v += coef * x(var);
    return v;
  }
};

// One two-sided row: lower <= lin(x) - (R(yaw) o)_axis <= upper. yaw_var < 0: the yaw is
// the constant fixed_yaw; has_offset false: no rotation term.
struct Row {
  Affine lin;
  bool has_offset = false;
  int yaw_var = -1;
  double fixed_yaw = 0.0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  int axis = 0;
  double lower = 0.0, upper = 0.0;
  double tighten = 0.0;  // lower + tighten <= value <= upper - tighten in the solve

  double Value(const Eigen::VectorXd& x) const {
    double v = lin.At(x);
    if (has_offset) {
      const double yaw = yaw_var >= 0 ? x(yaw_var) : fixed_yaw;
      const double c = std::cos(yaw), s = std::sin(yaw);
      v -= axis == 0 ? c * offset.x() - s * offset.y() : s * offset.x() + c * offset.y();
    }
    return v;
  }
  // d value / d yaw (only with has_offset and yaw_var >= 0).
  double YawDerivative(const Eigen::VectorXd& x) const {
    const double c = std::cos(x(yaw_var)), s = std::sin(x(yaw_var));
    return axis == 0 ? s * offset.x() + c * offset.y() : -(c * offset.x() - s * offset.y());
  }
  double Violation(const Eigen::VectorXd& x) const {
    const double v = Value(x);
    return std::max({0.0, v - upper, lower - v});
  }
};

class WindowProgram {
 public:
  WindowProgram(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x, double margin_m)
      : f_(formulation), miqp_x_(miqp_x) {
    const FootstepProblem& problem = f_.problem();
    const RobotModel& robot = *problem.robot;
    const FootstepVariables& v = f_.vars();
    const Miqp& miqp = f_.miqp();
    const int n = f_.num_legs(), N = f_.num_steps(), B = f_.num_configurations();
    trimmed_.assign(N, false);
    for (int i = n; i < N; ++i) trimmed_[i] = miqp_x(v.trim[i]) > 0.5;
    // Variables: (x, y, z) of each untrimmed new step, theta of each configuration but the start.
    step_var_.assign(N, -1);
    std::vector<double> start, lower, upper;
    auto add_var = [&](double x0, double lo, double hi) {
      start.push_back(x0);
      lower.push_back(lo);
      upper.push_back(hi);
      return static_cast<int>(start.size()) - 1;
    };
    for (int i = n; i < N; ++i) {
      if (trimmed_[i]) continue;
      const int xs[3] = {v.x[i], v.y[i], v.z[i]};
      step_var_[i] = add_var(miqp_x(xs[0]), miqp.var_lower(xs[0]), miqp.var_upper(xs[0]));
      for (int axis = 1; axis < 3; ++axis) add_var(miqp_x(xs[axis]), miqp.var_lower(xs[axis]), miqp.var_upper(xs[axis]));
    }
    // theta_var_[blk] < 0: the configuration's yaw is the start yaw. A configuration whose
    // first step is trimmed keeps the yaw of the one before when the formulation says so.
    theta_var_.assign(B, -1);
    for (int blk = 1; blk < B; ++blk) {
      const int t = v.theta[blk];
      if (f_.options().trimmed_configurations_hold_yaw && trimmed_[blk * n]) {
        theta_var_[blk] = theta_var_[blk - 1];
      } else {
        theta_var_[blk] = add_var(miqp_x(t), miqp.var_lower(t), miqp.var_upper(t));
      }
    }
    start_ = Eigen::Map<Eigen::VectorXd>(start.data(), static_cast<Eigen::Index>(start.size()));
    lower_ = Eigen::Map<Eigen::VectorXd>(lower.data(), static_cast<Eigen::Index>(lower.size()));
    upper_ = Eigen::Map<Eigen::VectorXd>(upper.data(), static_cast<Eigen::Index>(upper.size()));

    auto yaw_row = [&](int step, Row* row) {
      const int blk = step / n;
      if (blk == 0) {
        row->fixed_yaw = problem.start_step_yaw_rad.empty() ? problem.start_yaw_rad : problem.start_step_yaw_rad[step];
      } else {
        row->yaw_var = theta_var_[blk];
        row->fixed_yaw = problem.start_yaw_rad;
      }
    };
    auto coc = [&](int i, int axis) {
      Affine sum;
      for (int j = i - n + 1; j <= i; ++j) sum.Add(Pos(j, axis), 1.0 / n);
      return sum;
    };
    auto add_row = [&](Row row, double tighten) {
      if (row.lin.terms.empty() && !(row.has_offset && row.yaw_var >= 0)) return;  // a constant: nothing to solve
      row.tighten = tighten;
      const int r = static_cast<int>(rows_.size());
      if (std::isfinite(row.upper)) sides_.emplace_back(r, true);
      if (std::isfinite(row.lower)) sides_.emplace_back(r, false);
      rows_.push_back(std::move(row));
    };
    for (int i = n; i < N; ++i) {
      const Eigen::Vector2d o = robot.legs[f_.LegOfStep(i)].nominal_offset_body_m;
      for (int axis = 0; axis < 2; ++axis) {
        Row ref;
        ref.lin = Pos(i, axis);
        ref.lin.Add(coc(i, axis), -1.0);
        ref.has_offset = true;
        ref.offset = o;
        ref.axis = axis;
        yaw_row(i, &ref);
        ref.lower = -robot.l_bnd_m;
        ref.upper = robot.l_bnd_m;
        add_row(ref, margin_m);
        Row reach;
        reach.lin = Pos(i, axis);
        reach.lin.Add(coc(i - n, axis), -1.0);
        reach.has_offset = true;
        reach.offset = o;
        reach.axis = axis;
        yaw_row(i - n, &reach);
        reach.lower = -robot.d_lim_m;
        reach.upper = robot.d_lim_m;
        add_row(reach, margin_m);
      }
      Row dz;
      dz.lin = Pos(i, 2);
      dz.lin.Add(Pos(i - n, 2), -1.0);
      dz.lower = -robot.dz_max_m;
      dz.upper = robot.dz_max_m;
      add_row(dz, margin_m);
      if (!trimmed_[i]) {  // a trimmed step stands on its leg's previous foot, already in its region
        const ConvexRegion& region = problem.regions[ChosenRegion(i)];
        for (int k = 0; k < region.A.rows(); ++k) {
          Row face;
          for (int axis = 0; axis < 3; ++axis) face.lin.Add(Pos(i, axis), region.A(k, axis));
          face.lower = -kInfinity;
          face.upper = region.b(k);
          add_row(face, margin_m);
        }
      }
    }
    for (int blk = 1; blk < B; ++blk) {
      if (theta_var_[blk] == theta_var_[blk - 1] || theta_var_[blk] < 0) continue;  // held: no turn
      Row turn;
      turn.lin.terms.emplace_back(theta_var_[blk], 1.0);
      if (theta_var_[blk - 1] < 0) {
        turn.lin.constant = -problem.start_yaw_rad;
      } else {
        turn.lin.terms.emplace_back(theta_var_[blk - 1], -1.0);
      }
      turn.lower = -robot.max_yaw_change_rad;
      turn.upper = robot.max_yaw_change_rad;
      add_row(turn, 1e-9);
    }
    // The MIQP's objective on a full MIQP point: positions, centres of contacts, yaw and
    // its sin and cos follow the polisher's variables; the rest stays at the MIQP's values.
    for (int i = n; i < N; ++i) {
      const int xs[3] = {v.x[i], v.y[i], v.z[i]};
      for (int axis = 0; axis < 3; ++axis) full_map_.emplace_back(xs[axis], Pos(i, axis));
      full_map_.emplace_back(v.px[i], coc(i, 0));
      full_map_.emplace_back(v.py[i], coc(i, 1));
    }
  }

  const Eigen::VectorXd& start() const { return start_; }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }
  int num_inequalities() const { return static_cast<int>(selected_.size()); }

  // Adds to the inequalities the solver sees those within `slack` of their bound at x.
  // Far ones (the opposite sides of the boxes, most region faces) cannot become active
  // in the small moves of a polish, and SLSQP's time per iteration grows with their
  // number; MaxViolation still checks every one.
  void SelectNear(const Eigen::VectorXd& x, double slack) {
    std::vector<bool> in(sides_.size(), false);
    for (int k : selected_) in[k] = true;
    for (int k = 0; k < static_cast<int>(sides_.size()); ++k) {
      if (!in[k] && SideValue(x, k) > -slack) selected_.push_back(k);
    }
    std::sort(selected_.begin(), selected_.end());
  }

  void ClearSelection() { selected_.clear(); }

  Eigen::VectorXd FullPoint(const Eigen::VectorXd& x) const {
    Eigen::VectorXd full = miqp_x_;
    for (const auto& [index, expr] : full_map_) full(index) = expr.At(x);
    const FootstepVariables& v = f_.vars();
    for (int blk = 1; blk < f_.num_configurations(); ++blk) {
      const double t = Yaw(x, blk);
      full(v.theta[blk]) = t;
      full(v.s[blk]) = std::sin(t);
      full(v.c[blk]) = std::cos(t);
    }
    return full;
  }

  double Objective(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const {
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
        if (theta_var_[blk] < 0) continue;
        const double t = x(theta_var_[blk]);
        (*grad)(theta_var_[blk]) += g(v.theta[blk]) + std::cos(t) * g(v.s[blk]) - std::sin(t) * g(v.c[blk]);
      }
    }
    return miqp.Objective(full);
  }

  // Each selected finite side of a row as one inequality: value - (upper - tighten) <= 0
  // or (lower + tighten) - value <= 0.
  void Inequalities(const Eigen::VectorXd& x, Eigen::VectorXd* values, Eigen::MatrixXd* jacobian) const {
    const int m = num_inequalities();
    values->resize(m);
    if (jacobian != nullptr) jacobian->setZero(m, x.size());
    for (int k = 0; k < m; ++k) {
      const int side = selected_[k];
      (*values)(k) = SideValue(x, side);
      if (jacobian == nullptr) continue;
      const Row& row = rows_[sides_[side].first];
      const double sign = sides_[side].second ? 1.0 : -1.0;
      for (const auto& [var, coef] : row.lin.terms) (*jacobian)(k, var) += sign * coef;
      if (row.has_offset && row.yaw_var >= 0) (*jacobian)(k, row.yaw_var) += sign * row.YawDerivative(x);
    }
  }

  // Largest violation of the untightened constraints and the variable bounds.
  double MaxViolation(const Eigen::VectorXd& x) const {
    double worst = 0.0;
    for (const Row& row : rows_) worst = std::max(worst, row.Violation(x));
    for (int j = 0; j < x.size(); ++j) worst = std::max({worst, lower_(j) - x(j), x(j) - upper_(j)});
    return worst;
  }

  // The cost as a quadratic in x, with the sin and cos of each yaw linearised at xk
  // (the formulation's cost weighs theta, not s and c, so this is the exact cost; the
  // linearisation keeps it right should a cost on s or c appear). 0.5 x'Qx + c'x + constant.
  void QuadraticModel(const Eigen::VectorXd& xk, Eigen::SparseMatrix<double>* Q, Eigen::VectorXd* c,
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
      const int var = theta_var_[blk];
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

  // The selected sides linearised at xk as sparse rows: J x <= J xk - g(xk).
  void LinearisedSides(const Eigen::VectorXd& xk, Eigen::SparseMatrix<double, Eigen::RowMajor>* J,
                       Eigen::VectorXd* upper) const {
    const int m = num_inequalities();
    std::vector<Eigen::Triplet<double>> triplets;
    upper->resize(m);
    for (int k = 0; k < m; ++k) {
      const int side = selected_[k];
      const Row& row = rows_[sides_[side].first];
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

  // The yaw variables (each configuration's that is not held or fixed), once each.
  std::vector<int> YawVariables() const {
    std::vector<int> out;
    for (int var : theta_var_) {
      if (var >= 0 && (out.empty() || out.back() != var)) out.push_back(var);
    }
    return out;
  }

  std::vector<Footstep> Footsteps(const Eigen::VectorXd& x) const {
    std::vector<Footstep> steps = f_.ExtractFootsteps(miqp_x_);
    for (int i = f_.num_legs(); i < f_.num_steps(); ++i) {
      for (int axis = 0; axis < 3; ++axis) steps[i].position_world_m(axis) = Pos(i, axis).At(x);
      steps[i].yaw_rad = Yaw(x, i / f_.num_legs());
    }
    return steps;
  }

 private:
  double SideValue(const Eigen::VectorXd& x, int side) const {
    const Row& row = rows_[sides_[side].first];
    return sides_[side].second ? row.Value(x) - (row.upper - row.tighten) : (row.lower + row.tighten) - row.Value(x);
  }

  // Yaw of configuration blk >= 1.
  double Yaw(const Eigen::VectorXd& x, int blk) const {
    return theta_var_[blk] >= 0 ? x(theta_var_[blk]) : f_.problem().start_yaw_rad;
  }

  // Position of step j on one axis. Before the window: the history (or the start stance
  // when there is none), as in the formulation; a trimmed step is its leg's previous foot.
  Affine Pos(int j, int axis) const {
    const FootstepProblem& problem = f_.problem();
    const int n = f_.num_legs();
    while (j >= n && trimmed_[j]) j -= n;
    Affine a;
    if (j < 0 && !problem.history_feet_world_m.empty()) {
      a.constant = problem.history_feet_world_m[j + n](axis);
    } else if (j < n) {
      while (j < 0) j += n;
      a.constant = problem.start_feet_world_m[j](axis);
    } else {
      a.terms.emplace_back(step_var_[j] + axis, 1.0);
    }
    return a;
  }

  int ChosenRegion(int i) const {
    int best = -1;
    for (size_t r = 0; r < f_.problem().regions.size(); ++r) {
      const int h = f_.vars().region[i][r];
      if (h >= 0 && (best < 0 || miqp_x_(h) > miqp_x_(f_.vars().region[i][best]))) best = static_cast<int>(r);
    }
    MFP_CHECK(best >= 0);
    return best;
  }

  const MiqpFormulation& f_;
  const Eigen::VectorXd& miqp_x_;
  std::vector<bool> trimmed_;
  std::vector<int> step_var_, theta_var_;
  Eigen::VectorXd start_, lower_, upper_;
  std::vector<Row> rows_;
  std::vector<std::pair<int, bool>> sides_;  // (row, upper side?) of each inequality
  std::vector<int> selected_;                // the sides the solver sees (SelectNear)
  std::vector<std::pair<int, Affine>> full_map_;
};

struct SequentialQpResult {
  Eigen::VectorXd x;
  std::string stops;
};

// One QP of the sequential method at xk: the cost, every selected side linearised at xk,
// each yaw within `trust` of xk's; *predicted (may be null): the cost's decrease the QP
// promises, relative to the cost at xk. trust 0 holds the yaws: the rows are then linear in
// the footsteps and exact (R(yaw) is a constant matrix), so the QP's solution meets the
// exact constraints up to the interior point's tolerance. Returns xk when the solve fails.
Eigen::VectorXd QpStep(const WindowProgram& program, const Eigen::VectorXd& xk, double trust,
                       const Deadline& deadline, int* iterations, double* predicted) {
  const int nv = static_cast<int>(xk.size());
  Miqp qp;
  program.QuadraticModel(xk, &qp.Q, &qp.c, &qp.constant);
  // The cost scaled to about 1 at xk: the interior point's elastic rows (penalty 1e6 per
  // unit of violation) then hold exactly, as every dual stays far below the penalty.
  const double scale = 1.0 / std::max(1.0, std::abs(program.Objective(xk, nullptr)));
  qp.Q *= scale;
  qp.c *= scale;
  qp.constant *= scale;
  program.LinearisedSides(xk, &qp.A, &qp.row_upper);
  qp.row_lower = Eigen::VectorXd::Constant(qp.A.rows(), -kInfinity);
  qp.var_lower = program.lower();
  qp.var_upper = program.upper();
  const std::vector<int> yaws = program.YawVariables();
  for (int var : yaws) {
    qp.var_lower(var) = std::max(qp.var_lower(var), xk(var) - trust);
    qp.var_upper(var) = std::min(qp.var_upper(var), xk(var) + trust);
  }
  // The interior point wants lower < upper: a held variable gets 1e-9 of room (its row
  // terms move by at most 1e-9 x the offset, far inside the margin).
  qp.var_upper = qp.var_upper.cwiseMax(qp.var_lower + Eigen::VectorXd::Constant(nv, 1e-9));
  qp.is_integer.assign(nv, false);
  qp.var_names.assign(nv, "x");
  qp.row_names.assign(qp.A.rows(), "g");
  InteriorPointOptions ipm;
  ipm.deadline = deadline;
  // Tighter than the search's 1e-8: the rows' residual at convergence must sit well inside
  // the boxes' 1e-7 margin.
  ipm.tolerance = 1e-10;
  const RelaxationResult r = SolveQpInteriorPoint(qp, qp.var_lower, qp.var_upper, &xk, ipm);
  *iterations += r.iterations;
  // The model's decrease from xk, relative to the cost at xk (the model is exact at xk).
  if (predicted != nullptr) *predicted = r.status == RelaxationStatus::kSolved ? scale * program.Objective(xk, nullptr) - r.objective : kInfinity;
  if (r.x.size() != nv || !r.x.allFinite() || r.status == RelaxationStatus::kFailed) return xk;
  Eigen::VectorXd x = r.x.cwiseMax(program.lower()).cwiseMin(program.upper());
  if (trust == 0.0) {
    for (int var : yaws) x(var) = xk(var);
  }
  return x;
}

// Sequential convex programming with the integer assignment fixed. Each round: a QP with
// the yaws free within a trust region and sin/cos linearised at the current point, then
// the footsteps-alone QP at the yaws it chose (exact: R(yaw) is then constant); the
// round's point is kept when it is exact and, after the first, cheaper. Rounds stop when
// the model promises or the round wins less than sqp_relative_gain of the cost; a round
// that ends outside the constraints shrinks the trust region. When no round gives an
// exact point, the footsteps alone at the MIQP's yaws. Every kept point is exact, so the
// method can stop at any round with a usable plan.
SequentialQpResult PolishBySequentialQp(WindowProgram& program, const PolishOptions& options,
                                        double time_limit_s) {
  const auto start_time = std::chrono::steady_clock::now();
  const Deadline deadline = Deadline::After(time_limit_s);
  // Every side: the interior point is sparse, so far rows cost little.
  program.SelectNear(program.start(), kInfinity);
  int qps = 0, iterations = 0;
  auto feasible = [&](const Eigen::VectorXd& x) { return program.MaxViolation(x) <= options.feasibility_tolerance_m; };
  auto step = [&](const Eigen::VectorXd& xk, double trust, double* predicted) {
    ++qps;
    return QpStep(program, xk, trust, deadline, &iterations, predicted);
  };
  SequentialQpResult out;
  out.x = program.start();
  bool exact = false;
  double best = kInfinity, trust = options.sqp_trust_rad;
  int rounds = 0;
  std::string how = "yaws moved";
  const bool has_yaws = !program.YawVariables().empty();
  while (has_yaws && rounds < options.sqp_max_rounds && trust >= options.sqp_min_trust_rad && !deadline.Expired()) {
    ++rounds;
    double predicted = kInfinity;
    const Eigen::VectorXd moved = step(out.x, trust, &predicted);
    // The model (exact cost, linearised rows) promises too little to pay for a round.
    if (exact && predicted <= options.sqp_relative_gain) break;
    const Eigen::VectorXd trial = step(moved, 0.0, nullptr);
    if (!feasible(trial)) {  // the linearised step went too far from the circle
      trust *= 0.25;
      continue;
    }
    const double value = program.Objective(trial, nullptr);
    if (exact && value >= best) break;
    const double gain = best - value;
    out.x = trial;
    best = value;
    exact = true;
    if (gain <= options.sqp_relative_gain * std::max(1.0, std::abs(best))) break;
  }
  if (!exact && !deadline.Expired()) {
    // No yaw to move, or no round made the footsteps exact: the MIQP's yaws held.
    out.x = step(program.start(), 0.0, nullptr);
    how = "yaws held";
  }
  std::ostringstream msg;
  msg.precision(3);
  msg << "sequential QP: " << how << ", " << rounds << " rounds, " << qps << " QPs (" << iterations
      << " interior-point iterations), "
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count() << " s"
      << (feasible(out.x) ? "" : ", not exact");
  out.stops = msg.str();
  program.ClearSelection();
  return out;
}

void Accept(const WindowProgram& program, const Eigen::VectorXd& x, double time_s, PolishedWindow* out) {
  PolishReport& report = out->report;
  report.accepted = true;
  report.exact = true;
  report.time_s = time_s;
  report.excess_after = program.MaxViolation(x);
  report.objective_after = program.Objective(x, nullptr);
  out->footsteps = program.Footsteps(x);
}

// The polished point is not exact: the MIQP's footsteps stay. They are exact anyway when
// the chords happen to fit (or the window was planned with boxes tightened by the chords'
// error, see ChordErrorBound), and then there is nothing to report.
void Reject(const WindowProgram& program, const Eigen::VectorXd& x, double time_s, const std::string& stops,
            const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x, const PolishOptions& options,
            PolishedWindow* out) {
  PolishReport& report = out->report;
  report.stops = stops;
  report.time_s = time_s;
  report.excess_after = program.MaxViolation(x);
  report.exact = report.excess_before <= options.feasibility_tolerance_m;
  if (!report.exact) {
    std::ostringstream msg;
    msg.precision(3);
    msg << "polisher (" << stops << ") left a violation of " << report.excess_after
        << "; kept the MIQP's plan, whose exact-trigonometry violation is " << report.excess_before;
    report.message = msg.str();
  }
  out->footsteps = formulation.ExtractFootsteps(miqp_x);
}

}  // namespace

double ChordErrorBound(const MiqpFormulation& formulation) {
  const std::vector<double>& bp = formulation.yaw_breakpoints();
  double width = 0.0;
  for (size_t k = 1; k < bp.size(); ++k) width = std::max(width, bp[k] - bp[k - 1]);
  // The chord point at fraction t of a segment of width h, against the arc's point at
  // the same yaw (segment centred on 0): (cos(h/2) - cos(phi), (2t - 1) sin(h/2) - sin(phi)),
  // phi = (2t - 1) h / 2. Its largest length over a fine grid of t, plus the grid's
  // possible miss (the length's slope is below 1, the step below 1e-4 rad).
  double worst = 0.0;
  const int samples = 4096;
  for (int k = 0; k <= samples; ++k) {
    const double u = 2.0 * k / samples - 1.0, phi = 0.5 * u * width;
    worst = std::max(worst, std::hypot(std::cos(0.5 * width) - std::cos(phi), u * std::sin(0.5 * width) - std::sin(phi)));
  }
  double offset = 0.0;
  for (const LegModel& leg : formulation.problem().robot->legs) offset = std::max(offset, leg.nominal_offset_body_m.norm());
  return (worst + width / samples) * offset;
}

PolishedWindow PolishWindow(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x,
                            const PolishOptions& options) {
  PolishedWindow out;
  PolishReport& report = out.report;
  report.objective_before = report.objective_after = formulation.miqp().Objective(miqp_x);
  if (!options.enabled || formulation.num_configurations() < 2) {
    out.footsteps = formulation.ExtractFootsteps(miqp_x);
    return out;
  }
  const auto start_time = std::chrono::steady_clock::now();
  report.attempted = true;
  WindowProgram program(formulation, miqp_x, options.margin_m);
  if (program.start().size() == 0) {
    // Every step trimmed and every configuration holding the start yaw: the window keeps
    // the start stance, nothing to solve.
    report.attempted = false;
    report.exact = true;
    out.footsteps = formulation.ExtractFootsteps(miqp_x);
    return out;
  }
  report.excess_before = program.MaxViolation(program.start());
  NonlinearSolveOptions solve;
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count(); };
  auto time_left = [&] { return std::max(1e-6, options.time_limit_s - seconds()); };
  // The window's cost, scaled to about 1 at the start (SLSQP's stopping tests and merit
  // function weigh it against violations of a micrometre), by SLSQP from a given point.
  const double scale = 1.0 / std::max(1.0, std::abs(report.objective_before));
  auto minimise_cost = [&](const Eigen::VectorXd& from) {
    NonlinearProgram nlp;
    nlp.start = from;
    nlp.lower = program.lower();
    nlp.upper = program.upper();
    nlp.objective = [&](const Eigen::VectorXd& z, Eigen::VectorXd* grad) {
      const double f = program.Objective(z, grad);
      if (grad != nullptr) *grad *= scale;
      return scale * f;
    };
    nlp.num_inequalities = program.num_inequalities();
    nlp.inequalities = [&](const Eigen::VectorXd& z, Eigen::VectorXd* values, Eigen::MatrixXd* jacobian) {
      program.Inequalities(z, values, jacobian);
    };
    // Half of the time left, and a bounded number of evaluations (the scenarios' windows
    // take up to about 60; a run that oscillates for hundreds rarely ends better): the
    // projection after it needs time too.
    solve.time_limit_s = 0.5 * time_left();
    solve.max_evaluations = 300;
    return SolveNonlinearProgram(nlp, solve);
  };
  auto feasible = [&](const Eigen::VectorXd& x) { return program.MaxViolation(x) <= options.feasibility_tolerance_m; };
  // Feasibility projection: Gauss-Newton steps onto the constraints, each the nearest
  // point (Euclidean in metres and radians) to the current one that meets the rows
  // linearised there, by mfp's interior point. Only sin and cos are nonlinear, so each
  // step shrinks the violation quadratically (a millimetre, then about 1e-8 m).
  auto project = [&](Eigen::VectorXd x) {
    const int n = static_cast<int>(x.size());
    // The interior point wants lower < upper for every variable: a fixed variable (its
    // bounds meet) gets 1e-9 of room, far inside the 1e-6 feasibility tolerance.
    const Eigen::VectorXd var_upper = program.upper().cwiseMax(program.lower().array().matrix() +
                                                                Eigen::VectorXd::Constant(x.size(), 1e-9));
    Miqp qp;
    qp.Q.resize(n, n);
    qp.Q.setIdentity();
    qp.Q *= 2.0;
    qp.var_lower = program.lower();
    qp.var_upper = var_upper;
    qp.is_integer.assign(n, false);
    qp.var_names.assign(n, "x");
    for (int iteration = 0; iteration < 8 && seconds() < options.time_limit_s; ++iteration) {
      Eigen::VectorXd g;
      Eigen::MatrixXd jacobian;
      program.Inequalities(x, &g, &jacobian);
      if (g.size() == 0 || g.maxCoeff() <= 0.0) break;
      qp.c = -2.0 * x;
      qp.constant = x.squaredNorm();
      qp.A = jacobian.sparseView();
      qp.row_upper = jacobian * x - g;
      qp.row_lower = Eigen::VectorXd::Constant(g.size(), -kInfinity);
      qp.row_names.assign(g.size(), "g");
      const RelaxationResult r = SolveQpInteriorPoint(qp, qp.var_lower, qp.var_upper, &x, InteriorPointOptions{});
      if (r.x.size() != n || !r.x.allFinite()) break;
      x = r.x.cwiseMax(program.lower()).cwiseMin(program.upper());
    }
    return x;
  };
  std::string stop;
  if (options.sequential_qp) {
    const SequentialQpResult sqp = PolishBySequentialQp(program, options, time_left());
    stop = sqp.stops;
    if (feasible(sqp.x)) {
      report.stops = stop;
      Accept(program, sqp.x, seconds(), &out);
      return out;
    }
    if (!options.slsqp_fallback) {
      Reject(program, sqp.x, seconds(), stop, formulation, miqp_x, options, &out);
      return out;
    }
    stop += "; ";
  }
  auto attempt = [&]() {
    NonlinearSolveResult result = minimise_cost(program.start());
    stop += std::string(stop.empty() ? "" : "; ") + "cost: " + result.message + " (" +
            std::to_string(result.evaluations) + " evaluations)";
    if (!feasible(result.x) && seconds() < options.time_limit_s) {
      // SLSQP can stop outside the constraints (it stalls when started outside them, as
      // from some MIQP points of the URDF-only robots of tests/urdf_plan_test.cc, and its
      // objective test can end it before the constraints are met). Then: the projection
      // of its point, SLSQP again from there (inside), and a projection of that.
      const Eigen::VectorXd inside = project(result.x);
      stop += ", projected";
      if (feasible(inside) && seconds() < options.time_limit_s) {
        result = minimise_cost(inside);
        stop += ", cost: " + result.message + " (" + std::to_string(result.evaluations) + " evaluations)";
        if (!feasible(result.x)) result.x = project(result.x);
        if (!feasible(result.x)) result.x = inside;
      } else {
        result.x = inside;
      }
    }
    return result;
  };
  // The inequalities near the MIQP's point first; when the result violates any, the
  // solve is repeated with all of them.
  program.SelectNear(program.start(), options.active_slack);
  NonlinearSolveResult result = attempt();
  if (!feasible(result.x) && seconds() < options.time_limit_s) {
    program.SelectNear(program.start(), kInfinity);
    result = attempt();
  }
  if (seconds() < options.time_limit_s) {
    // SLSQP's and the projection's points meet the rows only to their tolerances (up to
    // the accepted 1e-6): the footsteps-alone QP at their yaws lands inside the margin.
    program.SelectNear(program.start(), kInfinity);
    int iterations = 0;
    const Eigen::VectorXd inside =
        QpStep(program, result.x, 0.0, Deadline::After(options.time_limit_s - seconds()), &iterations, nullptr);
    if (program.MaxViolation(inside) < program.MaxViolation(result.x)) {
      result.x = inside;
      stop += ", footsteps QP";
    }
  }
  if (feasible(result.x)) {
    report.stops = stop;
    Accept(program, result.x, seconds(), &out);
  } else {
    Reject(program, result.x, seconds(), stop, formulation, miqp_x, options, &out);
  }
  return out;
}

}  // namespace mfp
