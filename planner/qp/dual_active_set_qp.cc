#include "planner/qp/dual_active_set_qp.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <memory>

#include "base/check.h"
#include "planner/qp/internal/interior_point_kkt.h"

namespace mfp {
namespace {

// A rotation (cs, sn) with cs a + sn b = hypot(a, b) and -sn a + cs b = 0.
void Givens(double a, double b, double* cs, double* sn) {
  const double r = std::hypot(a, b);
  if (r == 0.0) {
    *cs = 1.0;
    *sn = 0.0;
    return;
  }
  *cs = a / r;
  *sn = b / r;
}

// Columns i and j of m replaced by cs m_i + sn m_j and -sn m_i + cs m_j.
void RotateColumns(Eigen::MatrixXd* m, int i, int j, double cs, double sn) {
  double* a = m->col(i).data();
  double* b = m->col(j).data();
  for (Eigen::Index r = 0; r < m->rows(); ++r) {
    const double ai = a[r], bi = b[r];
    a[r] = cs * ai + sn * bi;
    b[r] = -sn * ai + cs * bi;
  }
}

// A fingerprint of the problem's data but its variable bounds (position-weighted sums,
// infinite bounds skipped): the factors are reused only for the same data. (Other
// variable bounds are another node of the same problem; the regularisation's floor
// correction holds for any box.)
double Fingerprint(const Miqp& p) {
  double f = 0.0;
  auto add = [&f](const double* v, Eigen::Index size) {
    for (Eigen::Index i = 0; i < size; ++i) {
      if (std::isfinite(v[i])) f += static_cast<double>(i % 9973 + 1) * v[i];
    }
  };
  add(p.Q.valuePtr(), p.Q.nonZeros());
  add(p.A.valuePtr(), p.A.nonZeros());
  add(p.c.data(), p.c.size());
  add(p.row_lower.data(), p.row_lower.size());
  add(p.row_upper.data(), p.row_upper.size());
  return f + p.constant;
}

}  // namespace

bool DualActiveSetQp::Prepare(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  if (p.num_variables() == 0 || p.num_variables() > options_.max_variables) return false;
  if (!p.var_lower.allFinite() || !p.var_upper.allFinite() || !lower.allFinite() || !upper.allFinite()) return false;
  if ((lower.array() > upper.array()).any()) return false;
  const double fingerprint = Fingerprint(p);
  const bool same = problem_ == &p && key_rows_ == p.num_rows() && key_nnz_q_ == p.Q.nonZeros() &&
                    key_nnz_a_ == p.A.nonZeros() && key_fingerprint_ == fingerprint && n_ == p.num_variables();
  if (same) return true;
  warm_valid_ = false;
  snapshots_.assign(options_.snapshots, Snapshot());
  live_slot_ = -1;
  problem_ = &p;
  key_rows_ = p.num_rows();
  key_nnz_q_ = p.Q.nonZeros();
  key_nnz_a_ = p.A.nonZeros();
  key_fingerprint_ = fingerprint;
  if (!FactorHessian(p)) {
    problem_ = nullptr;
    return false;
  }
  return true;
}

bool DualActiveSetQp::FactorHessian(const Miqp& p) {
  n_ = p.num_variables();
  m_ = p.num_rows();
  A_ = &p.A;
  Q_ = &p.Q;
  constant_ = p.constant;
  c0_ = p.c;
  c_ = p.c;
  centre_ = Eigen::VectorXd::Zero(p.num_variables());
  eps_.resize(n_);
  for (int j = 0; j < n_; ++j) {
    const double range2 = std::max({1.0, p.var_lower(j) * p.var_lower(j), p.var_upper(j) * p.var_upper(j)});
    eps_(j) = options_.regularisation / range2;
  }
  H_ = Eigen::MatrixXd(p.Q);
  H_.diagonal() += eps_;
  Eigen::LLT<Eigen::MatrixXd> llt(H_);
  if (llt.info() != Eigen::Success) return false;
  // J0 = L^-T, upper triangular.
  Eigen::MatrixXd linv = Eigen::MatrixXd::Identity(n_, n_);
  llt.matrixL().solveInPlace(linv);
  J0_ = linv.transpose();
  if (!J0_.allFinite()) return false;
  row_norm_.resize(m_);
  for (int i = 0; i < m_; ++i) row_norm_(i) = std::max(1e-12, p.A.row(i).norm());
  rhs_.resize(2 * n_ + 2 * m_);
  is_equality_.assign(2 * n_ + 2 * m_, 0);
  for (int i = 0; i < m_; ++i) {
    rhs_(2 * n_ + i) = p.row_lower(i);
    rhs_(2 * n_ + m_ + i) = -p.row_upper(i);
    const bool eq = p.row_lower(i) == p.row_upper(i);
    is_equality_[2 * n_ + i] = is_equality_[2 * n_ + m_ + i] = eq;
  }
  R_ = Eigen::MatrixXd::Zero(n_, n_);
  return true;
}

void DualActiveSetQp::SetCentre(const Eigen::VectorXd* centre) {
  if (centre == nullptr) {
    centre_.setZero();
    c_ = c0_;
    return;
  }
  centre_ = *centre;
  c_ = c0_ - eps_.cwiseProduct(centre_);
}

void DualActiveSetQp::SetBounds(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  lower_ = lower;
  upper_ = upper;
  rhs_.head(n_) = lower;
  rhs_.segment(n_, n_) = -upper;
}

void DualActiveSetQp::ColdStart() {
  J_ = J0_;
  R_.setZero();
  active_.clear();
  is_active_.assign(2 * n_ + 2 * m_, 0);
  u_.resize(0);
  x_ = -(J_ * (J_.transpose() * c_));
  warm_solves_ = 0;
}

// x and the multipliers of the active set taken as equalities (see the header's
// reference): with J'N = [R; 0], y1 = R^-T b, y2 = -J2'c, x = J y, R u = y1 + J1'c.
void DualActiveSetQp::SolveForActiveSet() {
  const int k = static_cast<int>(active_.size());
  Eigen::VectorXd b(k);
  for (int i = 0; i < k; ++i) b(i) = rhs_(active_[i]);
  const auto Rk = R_.topLeftCorner(k, k).triangularView<Eigen::Upper>();
  const Eigen::VectorXd y1 = Rk.transpose().solve(b);
  const Eigen::VectorXd y2 = -(J_.rightCols(n_ - k).transpose() * c_);
  x_ = J_.leftCols(k) * y1 + J_.rightCols(n_ - k) * y2;
  u_ = Rk.solve(y1 + J_.leftCols(k).transpose() * c_);
}

// The last active set with the new right-hand sides, less the inequalities whose
// multipliers turn negative (most negative first): a dual-feasible start.
bool DualActiveSetQp::WarmStart() {
  ++warm_solves_;
  SolveForActiveSet();
  for (;;) {
    if (active_.empty()) return true;
    int worst = -1;
    double worst_u = -1e-12 * (1.0 + u_.cwiseAbs().maxCoeff());
    for (int i = 0; i < static_cast<int>(active_.size()); ++i) {
      if (!is_equality_[active_[i]] && u_(i) < worst_u) {
        worst_u = u_(i);
        worst = i;
      }
    }
    if (worst < 0) return true;
    DropFromFactors(worst);
    ++steps_;
    SolveForActiveSet();
  }
}

int DualActiveSetQp::BoundsChanged(const Snapshot& snapshot) const {
  int changed = 0;
  for (int j = 0; j < n_; ++j) changed += (snapshot.lower(j) != lower_(j)) + (snapshot.upper(j) != upper_(j));
  return changed;
}

// The stored state whose box differs from the new one in the fewest bounds becomes the
// live one (a copy unless it is the live one already).
void DualActiveSetQp::RestoreNearest() {
  int best = -1, best_changed = 0;
  for (int s = 0; s < static_cast<int>(snapshots_.size()); ++s) {
    if (snapshots_[s].used < 0) continue;
    const int changed = BoundsChanged(snapshots_[s]);
    if (best < 0 || changed < best_changed) {
      best = s;
      best_changed = changed;
    }
  }
  warm_valid_ = best >= 0;
  if (best < 0 || best == live_slot_) return;
  LoadSnapshot(best);
}

void DualActiveSetQp::LoadSnapshot(int slot) {
  const Snapshot& snap = snapshots_[slot];
  J_ = snap.J;
  const Eigen::Index k = static_cast<Eigen::Index>(snap.active.size());
  R_.setZero();
  R_.topLeftCorner(k, k) = snap.R.triangularView<Eigen::Upper>();
  active_ = snap.active;
  is_active_.assign(2 * n_ + 2 * m_, 0);
  for (int con : active_) is_active_[con] = 1;
  warm_solves_ = snap.warm_solves;
  live_slot_ = slot;
}

// Steps a warm solve may take before the interior point takes the node.
int DualActiveSetQp::WarmStepBudget() const {
  return static_cast<int>(std::ceil(options_.max_warm_steps_per_variable * n_));
}

// The size of the symmetric difference of two active sets.
int DualActiveSetQp::ActiveSetDistance(const std::vector<int>& from, const std::vector<int>& to) {
  for (int con : to) mark_[con] = 1;
  int distance = static_cast<int>(to.size());
  for (int con : from) distance += mark_[con] ? -1 : 1;
  for (int con : to) mark_[con] = 0;
  return distance;
}

// The factors of the active set target (less constraints dependent on those before it),
// built from the stored state nearest to it: its extra constraints dropped (the last
// first, the cheapest), the missing ones appended. The multipliers are left to
// SolveForActiveSet.
void DualActiveSetQp::BuildActiveSet(const std::vector<int>& target) {
  const int total = 2 * n_ + 2 * m_;
  std::vector<int> wanted;
  wanted.reserve(target.size());
  mark_.assign(total, 0);
  for (int con : target) {
    if (con < 0 || con >= total || mark_[con] || !std::isfinite(rhs_(con))) continue;
    mark_[con] = 1;
    wanted.push_back(con);
  }
  for (int con : wanted) mark_[con] = 0;
  int best = -1, best_distance = static_cast<int>(wanted.size());  // -1: the empty set
  for (int s = 0; s < static_cast<int>(snapshots_.size()); ++s) {
    if (snapshots_[s].used < 0 || snapshots_[s].warm_solves >= options_.warm_solves_before_rebuild) continue;
    const int distance = ActiveSetDistance(snapshots_[s].active, wanted);
    if (distance < best_distance || (distance == best_distance && s == live_slot_)) {
      best = s;
      best_distance = distance;
    }
  }
  if (best < 0) {
    ColdStart();
  } else if (best != live_slot_) {
    LoadSnapshot(best);
  }
  live_slot_ = -1;  // the factors change below
  u_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(active_.size()));
  for (int con : wanted) mark_[con] = 1;
  for (int i = static_cast<int>(active_.size()) - 1; i >= 0; --i) {
    if (mark_[active_[i]]) continue;
    DropFromFactors(i);
    ++steps_;
  }
  for (int con : wanted) {
    mark_[con] = 0;
    const int k = static_cast<int>(active_.size());
    if (is_active_[con] || k == n_) continue;
    const Eigen::VectorXd d = TransposedJTimesNormal(con);
    if (d.tail(n_ - k).squaredNorm() <= 1e-10 * d.squaredNorm()) continue;  // dependent
    AppendToFactors(con, d);
    ++steps_;
  }
  u_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(active_.size()));
}

// The live state stored for later nodes: over the slot of the same box, else the least
// recently used one.
void DualActiveSetQp::SaveSnapshot() {
  int slot = 0;
  for (int s = 0; s < static_cast<int>(snapshots_.size()); ++s) {
    if (snapshots_[s].used >= 0 && BoundsChanged(snapshots_[s]) == 0) {
      slot = s;
      break;
    }
    if (snapshots_[s].used < snapshots_[slot].used) slot = s;
  }
  Snapshot& snap = snapshots_[slot];
  snap.lower = lower_;
  snap.upper = upper_;
  snap.J = J_;
  const Eigen::Index k = static_cast<Eigen::Index>(active_.size());
  snap.R = R_.topLeftCorner(k, k).triangularView<Eigen::Upper>();  // the rest of R_ is zero
  snap.active = active_;
  snap.warm_solves = warm_solves_;
  snap.used = ++clock_;
  live_slot_ = slot;
}

double DualActiveSetQp::Slack(int con) const {
  if (con < n_) return x_(con) - rhs_(con);
  if (con < 2 * n_) return -x_(con - n_) - rhs_(con);
  if (con < 2 * n_ + m_) return ax_(con - 2 * n_) - rhs_(con);
  return -ax_(con - 2 * n_ - m_) - rhs_(con);
}

double DualActiveSetQp::NormalDot(int con, const Eigen::VectorXd& v) const {
  if (con < n_) return v(con);
  if (con < 2 * n_) return -v(con - n_);
  const bool upper_side = con >= 2 * n_ + m_;
  const int row = upper_side ? con - 2 * n_ - m_ : con - 2 * n_;
  double s = 0.0;
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(*A_, row); it; ++it) s += it.value() * v(it.col());
  return upper_side ? -s : s;
}

Eigen::VectorXd DualActiveSetQp::TransposedJTimesNormal(int con) const {
  if (con < n_) return J_.row(con).transpose();
  if (con < 2 * n_) return -J_.row(con - n_).transpose();
  const bool upper_side = con >= 2 * n_ + m_;
  const int row = upper_side ? con - 2 * n_ - m_ : con - 2 * n_;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n_);
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(*A_, row); it; ++it) {
    d.noalias() += it.value() * J_.row(it.col()).transpose();
  }
  return upper_side ? Eigen::VectorXd(-d) : d;
}

// The constraint of largest scaled violation (the first of equals, in constraint order).
// A constraint with a slack of at least 0 is met (the test asks the scaled slack below a
// negative threshold), so only violated ones pay for the scaling's division.
int DualActiveSetQp::MostViolated() const {
  const double tol = options_.feasibility_tolerance;
  int best = -1;
  double best_s = 0.0;
  auto consider = [&](int con, double slack, double scale) {
    if (slack >= 0.0 || is_active_[con] || !std::isfinite(rhs_(con))) return;
    const double s = slack / scale;
    if (s < -tol * (1.0 + std::abs(rhs_(con)) / scale) && s < best_s) {
      best_s = s;
      best = con;
    }
  };
  for (int j = 0; j < n_; ++j) consider(j, x_(j) - rhs_(j), 1.0);
  for (int j = 0; j < n_; ++j) consider(n_ + j, -x_(j) - rhs_(n_ + j), 1.0);
  for (int i = 0; i < m_; ++i) consider(2 * n_ + i, ax_(i) - rhs_(2 * n_ + i), row_norm_(i));
  for (int i = 0; i < m_; ++i) consider(2 * n_ + m_ + i, -ax_(i) - rhs_(2 * n_ + m_ + i), row_norm_(i));
  return best;
}

void DualActiveSetQp::AppendToFactors(int con, Eigen::VectorXd d) {
  const int k = static_cast<int>(active_.size());
  for (int i = n_ - 1; i > k; --i) {
    if (d(i) == 0.0) continue;
    double cs, sn;
    Givens(d(i - 1), d(i), &cs, &sn);
    d(i - 1) = cs * d(i - 1) + sn * d(i);
    d(i) = 0.0;
    RotateColumns(&J_, i - 1, i, cs, sn);
  }
  R_.col(k).head(k + 1) = d.head(k + 1);
  active_.push_back(con);
  is_active_[con] = 1;
}

void DualActiveSetQp::DropFromFactors(int position) {
  const int k = static_cast<int>(active_.size());
  for (int j = position + 1; j < k; ++j) R_.col(j - 1).head(j + 1) = R_.col(j).head(j + 1);
  R_.col(k - 1).setZero();
  for (int i = position; i < k - 1; ++i) {
    double cs, sn;
    Givens(R_(i, i), R_(i + 1, i), &cs, &sn);
    for (int col = i; col < k - 1; ++col) {
      const double a = R_(i, col), b = R_(i + 1, col);
      R_(i, col) = cs * a + sn * b;
      R_(i + 1, col) = -sn * a + cs * b;
    }
    R_(i + 1, i) = 0.0;
    RotateColumns(&J_, i, i + 1, cs, sn);
  }
  is_active_[active_[position]] = 0;
  active_.erase(active_.begin() + position);
  Eigen::VectorXd u(k - 1);
  u << u_.head(position), u_.tail(k - 1 - position);
  u_ = u;
}

// Goldfarb and Idnani's step 2: moves x and the multipliers until constraint p is met
// (then p joins the active set), dropping blocking constraints on the way.
DualActiveSetQp::Step DualActiveSetQp::AddConstraint(int p, const Deadline& deadline, double u_plus) {
  for (;;) {
    if (++steps_ > step_limit_ || deadline.Expired()) return Step::kLimit;
    const int k = static_cast<int>(active_.size());
    const Eigen::VectorXd d = TransposedJTimesNormal(p);
    const Eigen::VectorXd z = J_.rightCols(n_ - k) * d.tail(n_ - k);
    const Eigen::VectorXd r = R_.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(d.head(k));
    double t1 = kInfinity;
    int drop = -1;
    for (int j = 0; j < k; ++j) {
      if (is_equality_[active_[j]] || r(j) <= 0.0) continue;
      const double ratio = std::max(0.0, u_(j)) / r(j);
      if (ratio < t1) {
        t1 = ratio;
        drop = j;
      }
    }
    const double zn = d.tail(n_ - k).squaredNorm();
    const bool dependent = zn <= 1e-14 * d.squaredNorm();
    const double slack = NormalDot(p, x_) - rhs_(p);
    const double t2 = dependent ? kInfinity : std::max(0.0, -slack / zn);
    const double t = std::min(t1, t2);
    if (!std::isfinite(t)) return CertifiesInfeasible(p, r) ? Step::kInfeasible : Step::kFailed;
    u_.head(k) -= t * r;
    u_plus += t;
    if (!dependent) x_ += t * z;
    if (t2 <= t1) {
      AppendToFactors(p, d);
      u_.conservativeResize(k + 1);
      u_(k) = u_plus;
      return Step::kOptimal;
    }
    DropFromFactors(drop);
  }
}

// p's normal is (up to rounding) sum_j r_j n_j over the active set, every inequality's
// r_j <= 0: with y = (1 on p, -r_j on the active set), y_i >= 0 on every inequality (an
// equality row's side may take either sign), so every x meeting the constraints has
// sum_i y_i (n_i'x - b_i) >= 0, i.e. w'x >= beta. Checked in the problem's data: w and
// beta summed again from the rows, max over the box of w'x from the bounds, and a margin
// for the sums' rounding.
bool DualActiveSetQp::CertifiesInfeasible(int p, const Eigen::VectorXd& r) const {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n_);
  double beta = 0.0, magnitude = 0.0;
  auto add = [&](int con, double y) {
    if (con < n_) {
      w(con) += y;
    } else if (con < 2 * n_) {
      w(con - n_) -= y;
    } else {
      const bool upper_side = con >= 2 * n_ + m_;
      const int row = upper_side ? con - 2 * n_ - m_ : con - 2 * n_;
      const double signed_y = upper_side ? -y : y;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(*A_, row); it; ++it) {
        w(it.col()) += signed_y * it.value();
        magnitude += std::abs(signed_y * it.value());
      }
    }
    beta += y * rhs_(con);
    magnitude += std::abs(y * rhs_(con)) + std::abs(y);
  };
  add(p, 1.0);
  for (int j = 0; j < static_cast<int>(active_.size()); ++j) {
    if (!is_equality_[active_[j]] && r(j) > 0.0) return false;
    add(active_[j], -r(j));
  }
  double best = 0.0;  // max over the box of w'x
  for (int j = 0; j < n_; ++j) {
    if (w(j) == 0.0) continue;  // 0 * an infinite bound would make the sum NaN
    best += std::max(w(j) * lower_(j), w(j) * upper_(j));
    magnitude += std::abs(w(j)) * std::max(std::abs(lower_(j)), std::abs(upper_(j)));
  }
  return std::isfinite(best) && std::isfinite(beta) && best < beta - 1e-9 * (1.0 + magnitude);
}

DualActiveSetQp::Step DualActiveSetQp::Iterate(double cutoff, const Deadline& deadline) {
  for (;;) {
    if (deadline.Expired()) return Step::kLimit;
    ax_ = (*A_) * x_;
    if (std::isfinite(cutoff)) {
      const double floor = RegularisedObjective() - FloorCorrection();
      if (floor - 1e-9 * (1.0 + std::abs(floor)) >= cutoff) return Step::kCutoff;
    }
    const int p = MostViolated();
    if (p < 0) return Step::kOptimal;
    const Step s = AddConstraint(p, deadline);
    if (s != Step::kOptimal) return s;
  }
}

// H x + c - N u over the active set (the stationarity residual).
Eigen::VectorXd DualActiveSetQp::StationarityResidual(const Eigen::VectorXd& u) const {
  Eigen::VectorXd res = H_ * x_ + c_;
  for (size_t i = 0; i < active_.size(); ++i) {
    const int con = active_[i];
    if (con < n_) {
      res(con) -= u(i);
    } else if (con < 2 * n_) {
      res(con - n_) += u(i);
    } else {
      const bool upper_side = con >= 2 * n_ + m_;
      const int row = upper_side ? con - 2 * n_ - m_ : con - 2 * n_;
      const double signed_u = upper_side ? -u(i) : u(i);
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(*A_, row); it; ++it) {
        res(it.col()) -= signed_u * it.value();
      }
    }
  }
  return res;
}

// Iterative refinement of the multipliers: the updated factors lose digits on the
// planner's badly scaled QPs, and the floor pays for every unit of residual times the
// box's width. With J1'N = R, the correction R^-1 J1' res removes the residual's part in
// the active constraints' span.
void DualActiveSetQp::RefineMultipliers() {
  const int k = static_cast<int>(active_.size());
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::VectorXd res = StationarityResidual(u_);
    u_ += R_.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(J_.leftCols(k).transpose() * res);
  }
}

// At the optimum: x and the multipliers again straight from the factors (the steps'
// updates accumulate rounding), the constraints checked again, the multipliers refined.
DualActiveSetQp::Step DualActiveSetQp::Polish(Step step, double cutoff, const Deadline& deadline) {
  for (int round = 0; round < 2 && step == Step::kOptimal; ++round) {
    SolveForActiveSet();
    step = Iterate(cutoff, deadline);
  }
  if (step == Step::kOptimal) RefineMultipliers();
  return step;
}

// f(x) + sum_j (eps_j / 2) (x_j - centre_j)^2: the problem the factors solve, up to a
// constant (c_ = c0 - eps .* centre).
double DualActiveSetQp::RegularisedObjective() const {
  return 0.5 * x_.dot((*Q_) * x_) + 0.5 * (x_ - centre_).cwiseAbs2().dot(eps_) + c0_.dot(x_) + constant_;
}

// The regularisation's largest value over the node's box: min f >= min f_eps - this.
double DualActiveSetQp::FloorCorrection() const {
  double sum = 0.0;
  for (int j = 0; j < n_; ++j) {
    const double lo = lower_(j) - centre_(j), up = upper_(j) - centre_(j);
    sum += eps_(j) * std::max(lo * lo, up * up);
  }
  return 0.5 * sum;
}

// A floor that holds however inexact x and the multipliers are: for x' in the box that
// meets the rows, f_eps(x') >= f_eps(x) + g'(x' - x), g = H x + c = N u + res, so
//   f(x') >= f_eps(x) - correction - sum_i u_i (n_i'x - b_i) - sum_j |res_j| (u_j - l_j)
//            + sum over the active bounds of u_i (n_i'x' - b_i)   (the reduced costs).
void DualActiveSetQp::FillResult(const Miqp& problem, Step step, RelaxationResult* result) const {
  result->iterations = steps_;
  if (step == Step::kLimit) {
    result->status = RelaxationStatus::kIterationLimit;
    return;
  }
  if (step == Step::kInfeasible) {
    result->status = RelaxationStatus::kInfeasible;
    return;
  }
  if (step == Step::kFailed) {
    result->status = RelaxationStatus::kFailed;
    return;
  }
  const double f_eps = RegularisedObjective();
  if (step == Step::kCutoff) {
    result->status = RelaxationStatus::kCutoff;
    result->objective = f_eps - FloorCorrection() - 1e-9 * (1.0 + std::abs(f_eps));
    result->x = x_.cwiseMax(lower_).cwiseMin(upper_);
    return;
  }
  result->status = RelaxationStatus::kSolved;
  result->x = x_.cwiseMax(lower_).cwiseMin(upper_);
  result->objective = problem.Objective(result->x);
  result->lower_cost_rate = Eigen::VectorXd::Zero(n_);
  result->upper_cost_rate = Eigen::VectorXd::Zero(n_);
  Eigen::VectorXd u = u_;
  Eigen::VectorXd surplus(u.size());  // n_i'x - b_i of each active constraint
  double activity = 0.0;
  for (size_t i = 0; i < active_.size(); ++i) {
    const int con = active_[i];
    if (!is_equality_[con]) u(i) = std::max(0.0, u(i));
    surplus(i) = NormalDot(con, x_) - rhs_(con);
    activity += u(i) * surplus(i);
    if (con < n_) result->lower_cost_rate(con) = u(i);
    if (con >= n_ && con < 2 * n_) result->upper_cost_rate(con - n_) = u(i);
  }
  const Eigen::VectorXd res = StationarityResidual(u);
  const double slop = res.cwiseAbs().dot(upper_ - lower_);
  const double regularised_floor = f_eps - FloorCorrection() - activity - slop;
  // The box certificate of the unregularised problem at x (the active constraints, as
  // rows n_i'x >= b_i, dualised by u): its gradient residual g = Q x + c - N u is res less
  // the regularisation's gradient, so this floor pays eps_j |x_j - centre_j| per unit of
  // the box's width, not the regularisation's largest value over the box (what the
  // proximal centre needs). Both floors hold; the higher is reported.
  const Eigen::VectorXd g = res - eps_.cwiseProduct(x_ - centre_);
  const double f = 0.5 * x_.dot((*Q_) * x_) + c0_.dot(x_) + constant_;
  const double box_floor = BoxCertificate(f, u, -surplus, lower_, upper_, x_, [&g](int j) { return g(j); });
  const double floor = std::max(regularised_floor, box_floor);
  result->cost_floor = std::min(result->objective, floor - 1e-9 * (1.0 + std::abs(floor)));
  result->warm_token = std::make_shared<const std::vector<int>>(active_);
}

// The bounds of the start's active set that the child tightened past the parent's point
// are held at the parent's value (so the start is the parent's x and multipliers); each
// is returned with its own value, for EnterMovedBounds.
std::vector<std::pair<int, double>> DualActiveSetQp::HoldMovedBounds(const Eigen::VectorXd& parent_point) {
  std::vector<std::pair<int, double>> moved;
  for (int con : active_) {
    if (con >= 2 * n_) continue;
    const int j = con < n_ ? con : con - n_;
    const double held = con < n_ ? parent_point(j) : -parent_point(j);
    if (held < rhs_(con) - 1e-9 * (1.0 + std::abs(rhs_(con)))) {
      moved.emplace_back(con, rhs_(con));
      rhs_(con) = held;
    }
  }
  return moved;
}

// Each held bound takes its own value as a constraint the dual method adds: parallel to
// its held self, the first step of adding it drops the held one with its multiplier
// carried over (Goldfarb and Idnani's partial step), x unmoved; then it is added. A held
// bound the start dropped (negative multiplier) is only given its value: Iterate adds it
// if violated.
DualActiveSetQp::Step DualActiveSetQp::EnterMovedBounds(const std::vector<std::pair<int, double>>& moved,
                                                        const Deadline& deadline) {
  for (const auto& [con, value] : moved) rhs_(con) = value;
  for (const auto& [con, value] : moved) {
    if (!is_active_[con]) continue;
    const int position = static_cast<int>(std::find(active_.begin(), active_.end(), con) - active_.begin());
    const double carried = std::max(0.0, u_(position));
    DropFromFactors(position);
    ++steps_;
    ax_ = (*A_) * x_;
    if (NormalDot(con, x_) - rhs_(con) >= 0.0) continue;  // met already
    const Step s = AddConstraint(con, deadline, carried);
    if (s != Step::kOptimal) return s;
  }
  return Step::kOptimal;
}

RelaxationResult DualActiveSetQp::SolveFrom(const Miqp& problem, const Eigen::VectorXd& lower,
                                            const Eigen::VectorXd& upper, double cutoff, const Deadline& deadline,
                                            const std::vector<int>& start, const Eigen::VectorXd* parent_point) {
  RelaxationResult result;
  steps_ = 0;
  if (!Prepare(problem, lower, upper)) return result;  // kFailed
  const bool with_parent = parent_point != nullptr && parent_point->size() == n_;
  SetCentre(with_parent && options_.proximal_centre ? parent_point : nullptr);
  SetBounds(lower, upper);
  BuildActiveSet(start);
  std::vector<std::pair<int, double>> moved;
  if (with_parent && options_.enter_moved_bounds) moved = HoldMovedBounds(*parent_point);
  WarmStart();
  step_limit_ = steps_ + WarmStepBudget();
  warm_valid_ = true;
  Step step = EnterMovedBounds(moved, deadline);
  if (step == Step::kOptimal) step = Iterate(cutoff, deadline);
  step = Polish(step, cutoff, deadline);
  FillResult(problem, step, &result);
  const double loose = 1e-6 * (1.0 + std::abs(result.objective)) + FloorCorrection();
  if (step == Step::kOptimal && result.objective - result.cost_floor > loose) {
    const int steps = result.iterations;
    result = RelaxationResult();  // kFailed: drifted factors
    result.iterations = steps;
    warm_valid_ = false;
  }
  // Only a solved node has children to start from its state (a cutoff, an infeasible
  // node or a stopped solve has none; their siblings start from the parent's state):
  // the others' factors are not copied (a 2 n^2 copy per node).
  if (warm_valid_ && step == Step::kOptimal) {
    SaveSnapshot();
  } else {
    live_slot_ = -1;
  }
  return result;
}

std::vector<int> DualActiveSetQp::ActiveSetAt(const Miqp& problem, const Eigen::VectorXd& lower,
                                              const Eigen::VectorXd& upper, const RelaxationResult& solved) {
  const int n = problem.num_variables(), m = problem.num_rows();
  const Eigen::VectorXd& x = solved.x;
  const bool rates = solved.lower_cost_rate.size() == n && solved.row_lower_rate.size() == m;
  const double tol = 1e-5;  // relative distance to a side: the interior point stops at 1e-8 in mu, not at the side
  const double thr = 1e-6;  // multiplier relative to the largest: above the interior point's mu / slack of inactive sides
  double largest = 1.0;
  if (rates) {
    largest += std::max({solved.lower_cost_rate.maxCoeff(), solved.upper_cost_rate.maxCoeff(),
                         m ? solved.row_lower_rate.maxCoeff() : 0.0, m ? solved.row_upper_rate.maxCoeff() : 0.0});
  }
  // A side is active when x is on it and (if multipliers are given) its multiplier is
  // not negligible: a degenerate vertex has many more sides met than multipliers.
  auto active_side = [&](double distance, double bound, double rate) {
    return distance <= tol * (1.0 + std::abs(bound)) && (!rates || rate > thr * largest);
  };
  std::vector<int> active;
  for (int j = 0; j < n; ++j) {
    const double lo_rate = rates ? solved.lower_cost_rate(j) : 0.0, up_rate = rates ? solved.upper_cost_rate(j) : 0.0;
    const bool at_lower = active_side(x(j) - lower(j), lower(j), lo_rate);
    const bool at_upper = active_side(upper(j) - x(j), upper(j), up_rate);
    if (at_lower && at_upper) {
      active.push_back(up_rate > lo_rate ? n + j : j);
    } else if (at_lower) {
      active.push_back(j);
    } else if (at_upper) {
      active.push_back(n + j);
    }
  }
  const Eigen::VectorXd ax = problem.A * x;
  for (int i = 0; i < m; ++i) {
    const double scale = std::max(1e-12, problem.A.row(i).norm());
    const double lo = problem.row_lower(i), up = problem.row_upper(i);
    if (std::isfinite(lo) && active_side((ax(i) - lo) / scale, lo / scale, rates ? solved.row_lower_rate(i) : 0.0)) {
      active.push_back(2 * n + i);
    } else if (std::isfinite(up) &&
               active_side((up - ax(i)) / scale, up / scale, rates ? solved.row_upper_rate(i) : 0.0)) {
      active.push_back(2 * n + m + i);
    }
  }
  return active;
}

RelaxationResult DualActiveSetQp::Solve(const Miqp& problem, const Eigen::VectorXd& lower,
                                        const Eigen::VectorXd& upper, double cutoff, const Deadline& deadline) {
  RelaxationResult result;
  steps_ = 0;
  if (!Prepare(problem, lower, upper)) return result;  // kFailed
  SetCentre(nullptr);
  step_limit_ = options_.max_steps_per_size * (n_ + m_);
  SetBounds(lower, upper);
  RestoreNearest();
  const bool warm = warm_valid_ && warm_solves_ < options_.warm_solves_before_rebuild;
  if (warm) {
    WarmStart();
  } else {
    ColdStart();
  }
  warm_valid_ = true;
  Step step = Polish(Iterate(cutoff, deadline), cutoff, deadline);
  FillResult(problem, step, &result);
  // A warm solve whose floor lies far below its objective (drifted factors): once more cold.
  const double loose = 1e-6 * (1.0 + std::abs(result.objective)) + FloorCorrection();
  if (warm && step == Step::kOptimal && result.objective - result.cost_floor > loose) {
    ColdStart();  // steps_ keeps counting: iterations report both attempts
    step = Polish(Iterate(cutoff, deadline), cutoff, deadline);
    result = RelaxationResult();
    FillResult(problem, step, &result);
  }
  if (step == Step::kLimit) warm_valid_ = false;
  if (warm_valid_) {
    SaveSnapshot();
  } else {
    live_slot_ = -1;
  }
  return result;
}

}  // namespace mfp
