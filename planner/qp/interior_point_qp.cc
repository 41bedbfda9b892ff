#include "planner/qp/interior_point_qp.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <vector>

#include "base/check.h"
#include "planner/qp/internal/interior_point_kkt.h"
#include "planner/qp/internal/interior_point_polish.h"

namespace mfp {
namespace {

// Largest alpha in (0, 1] keeping v + alpha dv >= 0 (v > 0), given inverse_v = 1 / v:
// alpha = 1 / max(1, max_i -dv_i / v_i). One multiplying pass, no division, as it runs
// four times per iteration over every row and bound.
double MaxStep(const Eigen::VectorXd& inverse_v, const Eigen::VectorXd& dv) {
  return 1.0 / std::max(1.0, (-dv).cwiseProduct(inverse_v).maxCoeff());
}

// The floor below of any iterate (z >= 0): no point of the box that meets the rows costs
// less. The derivation is SetCostRates's. objective: 0.5 x'Qx + c'x + constant at w.
double LagrangianFloor(const InequalityForm& f, double objective, const Eigen::VectorXd& lower,
                       const Eigen::VectorXd& upper, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                       const Eigen::VectorXd& z, const Eigen::VectorXd& r_d, const Eigen::VectorXd& r_p) {
  const int n = f.n, E = f.elastic;
  const double elastic_cost = f.q.tail(E).dot(w.tail(E));
  double residual = 0.0;
  for (int j = 0; j < n; ++j) {
    residual += std::abs(r_d(j)) * std::max(upper(j) - w(j), w(j) - lower(j));
  }
  for (int k = 0; k < E; ++k) residual += std::abs(r_d(n + k)) * std::abs(w(n + k));
  return objective + elastic_cost + z.dot(r_p - s) - residual;
}

// The floor with the rows dualised and the box kept: for row multipliers z_R >= 0 (the
// elastic rows' duals) and any x of the box that meets the rows,
//   f(x) >= f(x) + z_R'(Gx - d_R) >= f(w) + z_R'(Gw - d_R) + g'(x - w),  g = Qw + c + G'z_R
// (convexity), and the least of g'(x - w) over the box is taken term by term. No bound
// multiplier enters, so neither do their residuals, which LagrangianFloor charges over
// each variable's whole box (the same certificate holds with rates max(0, g_j) from the
// lower end and max(0, -g_j) from the upper end). objective: f at w (with its constant).
double BoxFloor(const InequalityForm& f, double objective, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                const Eigen::VectorXd& w, const Eigen::VectorXd& z, const Eigen::VectorXd& r_d) {
  const int n = f.n, E = f.elastic;
  // r_d's x part is g plus the bound multipliers' part.
  return BoxCertificate(objective, z.head(E), f.G * w.head(n) - f.d.head(E), lower, upper, w.head(n),
                        [&](int j) { return r_d(j) - (z(2 * E + 2 * j) - z(2 * E + 2 * j + 1)); });
}

// The reduced-cost certificate of RelaxationResult from the final iterate. With the
// Lagrangian L(w) = f_el(w) + z'(C w - d) (f_el: objective plus elastic penalty), any
// point x of the box that meets the rows (so e = 0) satisfies
//   f(x) >= L(w) + sum_j z_l,j (x_j - l_j) + z_u,j (u_j - x_j)
// (the row terms left out are >= 0), and by convexity L(w) >= L(w*) + r_d'(w - w*),
// where L(w*) = f_el(w*) + z'(r_p - s). The residual term is bounded over the box and
// the elastic part (w_e = 0 against w*_e), so the floor holds for the inexact iterate.
// BoxFloor, the tighter floor on every node QP measured (docs/measurements.md, stop 35),
// becomes bound_floor; the rates stay the bound multipliers' (reduced-cost fixing reads them).
void SetCostRates(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                  const Eigen::VectorXd& w, const Eigen::VectorXd& s, const Eigen::VectorXd& z,
                  const Eigen::VectorXd& r_d, const Eigen::VectorXd& r_p, RelaxationResult* result) {
  const int n = f.n, E = f.elastic;
  result->cost_floor =
      std::min(result->objective, LagrangianFloor(f, result->objective, lower, upper, w, s, z, r_d, r_p));
  result->bound_floor =
      std::min(result->objective, std::max(result->cost_floor, BoxFloor(f, result->objective, lower, upper, w, z, r_d)));
  result->lower_cost_rate.resize(n);
  result->upper_cost_rate.resize(n);
  for (int j = 0; j < n; ++j) {
    result->upper_cost_rate(j) = std::max(0.0, z(2 * E + 2 * j));
    result->lower_cost_rate(j) = std::max(0.0, z(2 * E + 2 * j + 1));
  }
}

// Cold start: x in the middle of its box, e covering the rows' violations plus one,
// slacks of at least one, duals of one (half the penalty for the elastic pairs: their
// dual feasibility reads penalty = z(row) + z(e >= 0)).
void ColdStart(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
               const InteriorPointOptions& opt, Eigen::VectorXd* w, Eigen::VectorXd* s, Eigen::VectorXd* z) {
  const int n = f.n, E = f.elastic;
  *w = Eigen::VectorXd::Zero(n + E);
  for (int j = 0; j < n; ++j) (*w)(j) = 0.5 * (lower(j) + upper(j));
  const Eigen::VectorXd gx = f.G * w->head(n);
  for (int k = 0; k < E; ++k) (*w)(n + k) = std::max(0.0, gx(k) - f.d(k)) + 1.0;
  *s = (f.d - f.C(*w)).cwiseMax(1.0);
  *z = Eigen::VectorXd::Ones(f.d.size());
  z->head(2 * E).setConstant(0.5 * opt.elastic_penalty);
}

// Warm start from a point x0 (a parent node's solution): x near x0, and for every
// inequality a slack-dual pair with product mu0 = warm_start_complementarity. A row
// that x meets with slack r gets dual mu0 / r; its elastic variable takes what is left
// of the penalty as its dual and mu0 over that as its value (tiny). A row that x
// violates or nearly meets gets slack warm_start_min_slack, its elastic variable
// covering the rest. The cold start's products are of the order of the penalty, so the
// warm one starts many orders of magnitude closer to complementarity.
void WarmStart(const InequalityForm& f, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
               const Eigen::VectorXd& x0, const InteriorPointOptions& opt, Eigen::VectorXd* w, Eigen::VectorXd* s,
               Eigen::VectorXd* z) {
  const int n = f.n, E = f.elastic;
  const double mu0 = opt.warm_start_complementarity, min_slack = opt.warm_start_min_slack;
  const double penalty = opt.elastic_penalty;
  MFP_CHECK(mu0 > 0.0 && min_slack > 0.0 && opt.warm_start_pull > 0.0 && opt.warm_start_pull <= 1.0);
  *w = Eigen::VectorXd::Zero(n + E);
  *s = Eigen::VectorXd::Zero(f.d.size());
  *z = Eigen::VectorXd::Zero(f.d.size());
  for (int j = 0; j < n; ++j) {
    const double mid = 0.5 * (lower(j) + upper(j));
    (*w)(j) = (1.0 - opt.warm_start_pull) * std::clamp(x0(j), lower(j), upper(j)) + opt.warm_start_pull * mid;
    // Bound slacks strictly positive: on a box narrower than the rounding error of its
    // ends (bound propagation leaves such boxes) the pulled point can land on a bound,
    // and a zero slack made the duals infinite and the whole solve NaN (then Ipopt
    // solved it, 25 times slower). The slacks need not equal the distances exactly: the
    // primal residual carries the difference.
    const double floor = std::max(std::min(min_slack, 0.25 * (upper(j) - lower(j))),
                                  1e-9 * (1.0 + std::max(std::abs(lower(j)), std::abs(upper(j)))));
    (*s)(2 * E + 2 * j) = std::max(upper(j) - (*w)(j), floor);
    (*s)(2 * E + 2 * j + 1) = std::max((*w)(j) - lower(j), floor);
    (*z)(2 * E + 2 * j) = mu0 / (*s)(2 * E + 2 * j);
    (*z)(2 * E + 2 * j + 1) = mu0 / (*s)(2 * E + 2 * j + 1);
  }
  const Eigen::VectorXd gx = f.G * w->head(n);
  for (int k = 0; k < E; ++k) {
    const double slack = f.d(k) - gx(k);  // of the row without its elastic variable
    double e, z_row;
    if (slack >= min_slack) {
      z_row = std::min(mu0 / slack, 0.5 * penalty);
      e = mu0 / (penalty - z_row);
    } else {
      z_row = std::min(mu0 / min_slack, 0.5 * penalty);
      e = min_slack - slack;
    }
    (*w)(n + k) = e;
    (*s)(k) = slack + e;
    (*z)(k) = z_row;
    (*s)(E + k) = e;
    (*z)(E + k) = penalty - z_row;
  }
}

// One iterate's residuals: dual r_d = H w + q + C'z, primal r_p = C w + s - d,
// complementarity mu = s'z / m, and what the convergence test measures them against.
struct Residuals {
  Eigen::VectorXd r_d, r_p;
  double mu = 0.0;
  double dual_x = 0.0, dual_e = 0.0;  // infinity norms of r_d's x and e parts
  double objective = 0.0;             // 0.5 x'Qx + c'x, without the constant
  double scale_x = 0.0;               // the dual residual's scale
};

Residuals ResidualsAt(const InequalityForm& f, const Miqp& p, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                      const Eigen::VectorXd& z, double scale_c) {
  const int n = f.n;
  const int m = static_cast<int>(f.d.size());
  Residuals r;
  // Q x once per iteration: the dual residual, the objective and the dual scale use it.
  const Eigen::VectorXd qx = f.Q * w.head(n);
  r.r_d = f.q;
  r.r_d.head(n) += qx;
  r.r_d += f.Ct(z);
  r.r_p = f.C(w) + s - f.d;
  r.mu = s.dot(z) / m;
  r.dual_x = r.r_d.head(n).lpNorm<Eigen::Infinity>();
  r.dual_e = f.elastic ? r.r_d.tail(f.elastic).lpNorm<Eigen::Infinity>() : 0.0;
  r.objective = 0.5 * w.head(n).dot(qx) + p.c.dot(w.head(n));
  r.scale_x = scale_c + qx.lpNorm<Eigen::Infinity>();
  return r;
}

// Converged: primal feasible and complementary to the tolerance, and dual feasible to
// the tolerance or, once complementarity is far below it, to an acceptable level.
// (Normal equations lose digits in the duals of active bounds as sigma grows; the
// objective has settled long before, which is what a bound needs.)
bool Converged(const Residuals& r, const InteriorPointOptions& opt, double scale_d) {
  const bool primal_ok = r.r_p.lpNorm<Eigen::Infinity>() <= opt.tolerance * scale_d;
  const bool complementary = r.mu <= opt.tolerance * (1.0 + std::abs(r.objective));
  const bool dual_ok = r.dual_x <= opt.tolerance * r.scale_x && r.dual_e <= opt.tolerance * opt.elastic_penalty;
  const bool dual_acceptable = complementary && r.dual_x <= opt.acceptable_dual * r.scale_x &&
                               r.dual_e <= opt.acceptable_dual * opt.elastic_penalty;
  return primal_ok && complementary && (dual_ok || dual_acceptable);
}

// The rows' multipliers: the duals of their one-sided rows, in Build's order.
void SetRowRates(const Miqp& p, const Eigen::VectorXd& z, RelaxationResult* result) {
  result->row_lower_rate = Eigen::VectorXd::Zero(p.num_rows());
  result->row_upper_rate = Eigen::VectorXd::Zero(p.num_rows());
  int k = 0;
  for (int i = 0; i < p.num_rows(); ++i) {
    if (std::isfinite(p.row_upper(i))) result->row_upper_rate(i) = std::max(0.0, z(k++));
    if (std::isfinite(p.row_lower(i))) result->row_lower_rate(i) = std::max(0.0, z(k++));
  }
}

// The result at a converged iterate: infeasible when an elastic variable stays above
// the threshold, else solved with its reduced-cost certificate.
RelaxationResult ConvergedResult(const InequalityForm& f, const Miqp& p, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper, const Eigen::VectorXd& w, const Eigen::VectorXd& s,
                                 const Eigen::VectorXd& z, const Residuals& r, const InteriorPointOptions& opt,
                                 double scale_d) {
  RelaxationResult result;
  result.x = w.head(f.n);
  result.objective = r.objective + p.constant;
  const double violation = f.elastic ? w.tail(f.elastic).maxCoeff() : 0.0;
  const double threshold =
      std::max(opt.infeasible_violation, opt.infeasible_violation_per_tolerance * opt.tolerance * scale_d);
  result.status = violation > threshold ? RelaxationStatus::kInfeasible : RelaxationStatus::kSolved;
  if (result.status == RelaxationStatus::kSolved) {
    SetCostRates(f, lower, upper, w, s, z, r.r_d, r.r_p, &result);
    SetRowRates(p, z, &result);
  }
  return result;
}

// The Newton system of one iterate, (H + C'SC) dw = t with S = diag(sigma), sigma = z / s.
// Its diagonal block for the elastic variables (each appears in its own row and in
// e >= 0 only) is eliminated: with S1, S2 the weights of those two rows and Sb the bound
// rows' weights,
//   K dx = t_x + G' (S1 / (S1 + S2) t_e),  K = Q + G' diag(S1 S2 / (S1 + S2)) G + Sb,
//   de = (t_e + S1 G dx) / (S1 + S2).
// K has the size of x alone.
class NewtonSystem {
 public:
  NewtonSystem(const InequalityForm& f, const Eigen::VectorXd& s, const Eigen::VectorXd& z, const Residuals& r)
      : f_(f), r_(r), inverse_s_(s.cwiseInverse()), sigma_(z.cwiseProduct(inverse_s_)) {
    const int n = f.n, E = f.elastic;
    s1_ = sigma_.head(E);
    const Eigen::VectorXd s2 = sigma_.segment(E, E);
    s12_ = s1_ + s2;
    row_weight_ = s1_.cwiseProduct(s2).cwiseQuotient(s12_);
    bound_weight_.resize(n);
    for (int j = 0; j < n; ++j) bound_weight_(j) = sigma_(2 * E + 2 * j) + sigma_(2 * E + 2 * j + 1);
  }

  const Eigen::VectorXd& inverse_s() const { return inverse_s_; }
  bool Factor(KktSolver* kkt) const { return kkt->Factor(row_weight_, bound_weight_); }

  // Newton direction for a complementarity target rc:
  //   (H + C'SC) dw = -r_d - C'(S r_p + S^-1 rc),  ds = -r_p - C dw,  dz = S(C dw + r_p) + S^-1 rc.
  // With v = S r_p + S^-1 rc split by row groups (v_R the elastic rows, v_P their
  // e >= 0 rows, v_U and v_L the bound pairs), t = -r_d - C'v reads
  //   t_x = -r_d,x - G'v_R - (v_U - v_L),  t_e = -r_d,e + v_R + v_P,
  // so the right-hand side K dx = t_x + G'(S1 t_e / (S1 + S2)) needs one product with
  // G' and C dw one with G (G dx, which de needs too).
  void Direction(const KktSolver& kkt, const Eigen::VectorXd& rc, double tolerance, int refinement_steps,
                 Eigen::VectorXd* dw, Eigen::VectorXd* ds, Eigen::VectorXd* dz) const {
    const int n = f_.n, E = f_.elastic;
    const int m = static_cast<int>(f_.d.size());
    const Eigen::VectorXd& r_d = r_.r_d;
    const Eigen::VectorXd& r_p = r_.r_p;
    const Eigen::VectorXd v = sigma_.cwiseProduct(r_p) + rc.cwiseProduct(inverse_s_);
    const Eigen::VectorXd t_e = -r_d.tail(E) + v.head(E) + v.segment(E, E);
    const Eigen::VectorXd row_part = s1_.cwiseProduct(t_e).cwiseQuotient(s12_) - v.head(E);
    Eigen::VectorXd rhs_x = f_.Gt * row_part - r_d.head(n);
    for (int j = 0; j < n; ++j) rhs_x(j) -= v(2 * E + 2 * j) - v(2 * E + 2 * j + 1);
    const Eigen::VectorXd dx = kkt.Solve(rhs_x, tolerance, refinement_steps);
    const Eigen::VectorXd g_dx = f_.G * dx;
    dw->resize(n + E);
    dw->head(n) = dx;
    dw->tail(E) = (t_e + s1_.cwiseProduct(g_dx)).cwiseQuotient(s12_);
    Eigen::VectorXd c_dw(m);  // C dw from G dx
    c_dw.head(E) = g_dx - dw->tail(E);
    c_dw.segment(E, E) = -dw->tail(E);
    for (int j = 0; j < n; ++j) {
      c_dw(2 * E + 2 * j) = dx(j);
      c_dw(2 * E + 2 * j + 1) = -dx(j);
    }
    *ds = -r_p - c_dw;
    *dz = sigma_.cwiseProduct(c_dw + r_p) + rc.cwiseProduct(inverse_s_);
  }

 private:
  const InequalityForm& f_;
  const Residuals& r_;
  const Eigen::VectorXd inverse_s_;
  const Eigen::VectorXd sigma_;
  Eigen::VectorXd s1_, s12_, row_weight_, bound_weight_;
};

// Mehrotra's predictor-corrector step from (w, s, z), 0.99 of the way to the boundary.
void PredictorCorrectorStep(const NewtonSystem& newton, const KktSolver& kkt, double mu,
                            const InteriorPointOptions& opt, Eigen::VectorXd* w, Eigen::VectorXd* s,
                            Eigen::VectorXd* z) {
  const int m = static_cast<int>(s->size());
  const Eigen::VectorXd inverse_z = z->cwiseInverse();
  const Eigen::VectorXd& inverse_s = newton.inverse_s();
  Eigen::VectorXd dw, ds, dz;
  newton.Direction(kkt, -s->cwiseProduct(*z), opt.tolerance, opt.predictor_refinement_steps, &dw, &ds,
                   &dz);  // predictor (affine scaling)
  const double alpha_aff = std::min(MaxStep(inverse_s, ds), MaxStep(inverse_z, dz));
  const double mu_aff = (*s + alpha_aff * ds).dot(*z + alpha_aff * dz) / m;
  const double centering = std::pow(mu_aff / mu, 3);
  const Eigen::VectorXd rc =
      -s->cwiseProduct(*z) - ds.cwiseProduct(dz) + Eigen::VectorXd::Constant(m, centering * mu);
  newton.Direction(kkt, rc, opt.tolerance, opt.refinement_steps, &dw, &ds, &dz);  // corrector
  const double alpha = std::min(1.0, 0.99 * std::min(MaxStep(inverse_s, ds), MaxStep(inverse_z, dz)));
  *w += alpha * dw;
  *s += alpha * ds;
  *z += alpha * dz;
}

// The crossover's result: x, objective and both floors the polished point's (its box
// certificate, rates max(0, g_j) from the lower end and max(0, -g_j) from the upper end:
// BoxFloor's with exact multipliers), the rows' rates its multipliers.
RelaxationResult PolishedResult(const Miqp& p, const ActiveSetPolish& polish, int iterations, int attempts) {
  RelaxationResult result;
  result.status = RelaxationStatus::kSolved;
  result.x = polish.x;
  result.objective = polish.objective;
  result.iterations = iterations;
  result.cost_floor = result.bound_floor = polish.floor;
  result.lower_cost_rate = polish.gradient.cwiseMax(0.0);
  result.upper_cost_rate = (-polish.gradient).cwiseMax(0.0);
  SetRowRates(p, polish.z_rows, &result);
  result.polish_attempts = attempts;
  result.polished = 1;
  return result;
}

// Whether to try the crossover at this iterate: once at polish_tolerance, once more at
// convergence (not twice at one iterate), and only while the elastic variables say the
// rows can be met (an infeasible node's guess cannot pass the checks).
bool PolishDue(const InequalityForm& f, const Residuals& r, const Eigen::VectorXd& w, const InteriorPointOptions& opt,
               double scale_d, bool converged, int attempts) {
  if (opt.polish_tolerance <= 0.0 || attempts >= 2 || (!converged && attempts >= 1)) return false;
  InteriorPointOptions loose = opt;
  loose.tolerance = std::max(opt.tolerance, opt.polish_tolerance);
  if (!converged && !Converged(r, loose, scale_d)) return false;
  if (converged && attempts == 1 && loose.tolerance == opt.tolerance) return false;  // tried at this iterate
  const double violation = f.elastic ? w.tail(f.elastic).maxCoeff() : 0.0;
  return violation <= std::max(opt.infeasible_violation, opt.infeasible_violation_per_tolerance * loose.tolerance * scale_d);
}

}  // namespace

RelaxationResult SolveQpInteriorPoint(const Miqp& p, const Eigen::VectorXd& lower,
                                      const Eigen::VectorXd& upper, const Eigen::VectorXd* warm_start,
                                      const InteriorPointOptions& opt) {
  const InequalityForm f = BuildInequalityForm(p, lower, upper, opt.elastic_penalty);
  const int n = f.n;
  RelaxationResult result;

  Eigen::VectorXd w, s, z;
  if (warm_start != nullptr) {
    WarmStart(f, lower, upper, *warm_start, opt, &w, &s, &z);
  } else {
    ColdStart(f, lower, upper, opt, &w, &s, &z);
  }

  const double scale_d = 1.0 + f.d.lpNorm<Eigen::Infinity>();
  const double scale_c = 1.0 + p.c.lpNorm<Eigen::Infinity>();
  // K = Q + G' diag(w) G + diag(b) keeps one sparsity pattern through the solve; its
  // values are scattered in place each iteration instead of forming sparse products.
  if (KktProductTerms(f) > opt.max_kkt_terms) {
    result.status = RelaxationStatus::kFailed;  // too large; see max_kkt_terms
    result.over_work_budget = true;
    result.x = w.head(n);
    result.objective = p.Objective(result.x);
    return result;
  }
  KktSolver kkt(f, opt.deadline);

  int polish_attempts = 0;
  double polish_floor = -kInfinity;  // the best certificate of the rejected guesses
  for (int iter = 0; iter < opt.max_iterations && kkt.ready(); ++iter) {
    result.iterations = iter;
    if (opt.deadline.Expired()) break;  // kIterationLimit below
    const Residuals r = ResidualsAt(f, p, w, s, z, scale_c);
    const bool converged = Converged(r, opt, scale_d);
    // The crossover runs only with time left (checked just above) and costs at most
    // ActiveSetPolishOptions::max_rounds factorisations of a KKT system no larger than
    // this solve's, which max_kkt_terms has already bounded: a few iterations' work.
    if (PolishDue(f, r, w, opt, scale_d, converged, polish_attempts)) {
      ++polish_attempts;
      const ActiveSetPolish polish = PolishActiveSet(f, p, lower, upper, w, s, z, opt.polish);
      if (polish.accepted) return PolishedResult(p, polish, iter, polish_attempts);
      polish_floor = std::max(polish_floor, polish.floor);
    }
    if (converged) {
      RelaxationResult done = ConvergedResult(f, p, lower, upper, w, s, z, r, opt, scale_d);
      done.iterations = iter;
      done.polish_attempts = polish_attempts;
      // A rejected guess's box certificate still holds (any point, multipliers >= 0).
      if (done.status == RelaxationStatus::kSolved) {
        done.bound_floor = std::max(done.bound_floor, std::min(done.objective, polish_floor));
      }
      return done;
    }
    // A node that cannot beat the incumbent is settled as soon as the floor proves it,
    // often many iterations before convergence.
    if (opt.cutoff < kInfinity) {
      const double floor = LagrangianFloor(f, r.objective + p.constant, lower, upper, w, s, z, r.r_d, r.r_p);
      if (floor >= opt.cutoff) {
        result.status = RelaxationStatus::kCutoff;
        result.x = w.head(n);
        result.objective = floor;
        return result;
      }
    }
    const NewtonSystem newton(f, s, z, r);
    if (!newton.Factor(&kkt)) break;
    PredictorCorrectorStep(newton, kkt, r.mu, opt, &w, &s, &z);
  }
  result.status = RelaxationStatus::kIterationLimit;
  result.polish_attempts = polish_attempts;
  result.x = w.head(n);
  result.objective = p.Objective(result.x);
  return result;
}

}  // namespace mfp
