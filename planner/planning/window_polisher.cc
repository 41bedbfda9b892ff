#include "planner/planning/internal/window_polisher.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

#include <Eigen/Sparse>

#include "base/check.h"
#include "planner/nlp/nonlinear_program.h"
#include "planner/planning/internal/window_program.h"
#include "planner/qp/interior_point_qp.h"

namespace mfp {
namespace {

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
  const double worst = ChordPointError(LargestSegment(formulation.yaw_breakpoints()));
  double offset = 0.0;
  for (const LegModel& leg : formulation.problem().robot->legs) offset = std::max(offset, leg.nominal_offset_body_m.norm());
  return worst * offset;
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
