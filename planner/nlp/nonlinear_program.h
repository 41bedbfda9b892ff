#pragma once
// A small smooth nonlinear program and a local solver for it, independent of any solver
// library: minimise f(x) subject to g(x) <= 0 (componentwise) and lower <= x <= upper,
// from a given start point, within a time limit. The solver behind it (NLopt's SLSQP) is
// confined to nlopt_program_solver.cc.
#include <Eigen/Core>
#include <functional>
#include <string>

namespace mfp {

struct NonlinearProgram {
  Eigen::VectorXd start, lower, upper;
  // f(x); fills grad (size n) when it is non-null.
  std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd* grad)> objective;
  int num_inequalities = 0;
  // g(x) into values (size m); fills jacobian (m x n) when it is non-null.
  std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd* values, Eigen::MatrixXd* jacobian)> inequalities;
};

struct NonlinearSolveOptions {
  double time_limit_s = 0.5;
  double relative_tolerance = 1e-10;  // on f and on x between iterations
  int max_evaluations = 2000;
};

struct NonlinearSolveResult {
  bool converged = false;   // the solver stopped at a point it reports as a local optimum
  Eigen::VectorXd x;        // its last (best) point; check feasibility yourself
  double objective = 0.0;
  int evaluations = 0;      // of the objective
  std::string message;      // the solver's stop reason, for messages
};

// Sequential quadratic programming from program.start (any point; it need not be
// feasible). Never throws for solver trouble: it is reported in the result.
NonlinearSolveResult SolveNonlinearProgram(const NonlinearProgram& program, const NonlinearSolveOptions& options);

}  // namespace mfp
