// The only file of the planner core that sees NLopt: NonlinearProgram -> LD_SLSQP.
#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <vector>

#include "base/check.h"
#include "planner/nlp/nonlinear_program.h"

namespace mfp {
namespace {

struct Callbacks {
  const NonlinearProgram* program;
  int evaluations = 0;
  Eigen::VectorXd x, grad, values;
  Eigen::MatrixXd jacobian;
};

double Objective(unsigned n, const double* x, double* grad, void* data) {
  Callbacks& cb = *static_cast<Callbacks*>(data);
  ++cb.evaluations;
  cb.x = Eigen::Map<const Eigen::VectorXd>(x, n);
  const double f = cb.program->objective(cb.x, grad != nullptr ? &cb.grad : nullptr);
  if (grad != nullptr) Eigen::Map<Eigen::VectorXd>(grad, n) = cb.grad;
  return f;
}

void Inequalities(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
  Callbacks& cb = *static_cast<Callbacks*>(data);
  cb.x = Eigen::Map<const Eigen::VectorXd>(x, n);
  cb.program->inequalities(cb.x, &cb.values, grad != nullptr ? &cb.jacobian : nullptr);
  MFP_CHECK(cb.values.size() == static_cast<Eigen::Index>(m));
  Eigen::Map<Eigen::VectorXd>(result, m) = cb.values;
  if (grad != nullptr) {
    // NLopt wants row-major m x n: grad[i * n + j] = d g_i / d x_j.
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(grad, m, n) = cb.jacobian;
  }
}

}  // namespace

NonlinearSolveResult SolveNonlinearProgram(const NonlinearProgram& program, const NonlinearSolveOptions& options) {
  const int n = static_cast<int>(program.start.size());
  MFP_CHECK(n > 0 && program.lower.size() == n && program.upper.size() == n && program.objective);
  NonlinearSolveResult out;
  Callbacks cb{&program, 0, {}, Eigen::VectorXd(n), {}, {}};
  std::vector<double> x(program.start.data(), program.start.data() + n);
  for (int j = 0; j < n; ++j) x[j] = std::clamp(x[j], program.lower(j), program.upper(j));
  try {
    nlopt::opt opt(nlopt::LD_SLSQP, static_cast<unsigned>(n));
    opt.set_lower_bounds(std::vector<double>(program.lower.data(), program.lower.data() + n));
    opt.set_upper_bounds(std::vector<double>(program.upper.data(), program.upper.data() + n));
    opt.set_min_objective(Objective, &cb);
    if (program.num_inequalities > 0) {
      opt.add_inequality_mconstraint(Inequalities, &cb, std::vector<double>(program.num_inequalities, 0.0));
    }
    opt.set_ftol_rel(options.relative_tolerance);
    opt.set_xtol_rel(options.relative_tolerance);
    opt.set_maxeval(options.max_evaluations);
    opt.set_maxtime(options.time_limit_s);
    double f = 0.0;
    const nlopt::result r = opt.optimize(x, f);
    out.converged = r == nlopt::SUCCESS || r == nlopt::FTOL_REACHED || r == nlopt::XTOL_REACHED ||
                    r == nlopt::STOPVAL_REACHED;
    out.message = r == nlopt::MAXTIME_REACHED   ? "time limit"
                  : r == nlopt::MAXEVAL_REACHED ? "evaluation limit"
                  : r == nlopt::STOPVAL_REACHED ? "target reached"
                  : r == nlopt::FTOL_REACHED    ? "objective converged"
                  : r == nlopt::XTOL_REACHED    ? "point converged"
                                                : "stopped (NLopt result " + std::to_string(static_cast<int>(r)) + ")";
    out.objective = f;
  } catch (const nlopt::roundoff_limited&) {
    // Roundoff-limited stops still leave x at the best point found; the caller checks it.
    out.converged = true;
    out.message = "roundoff limited";
  } catch (const std::exception& e) {
    out.message = std::string("failed: ") + e.what();
  }
  out.evaluations = cb.evaluations;
  out.x = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
  out.objective = program.objective(out.x, nullptr);
  return out;
}

}  // namespace mfp
