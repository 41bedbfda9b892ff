#pragma once
// Ipopt backend of RelaxationSolver. Ipopt headers stay inside the .cc file.
#include <memory>
#include <string>

#include "planner/qp/relaxation_solver.h"

namespace mfp {

struct IpoptSettings {
  double tolerance = 1e-8;       // Ipopt "tol"
  int max_iterations = 500;      // per relaxation
  double max_cpu_time_s = 10.0;  // per relaxation
  // Mehrotra's predictor-corrector is Ipopt's suggestion for convex QPs, but with it Ipopt
  // 3.11 spends its whole iteration limit on infeasible nodes, which the default mode
  // detects early (docs/measurements.md).
  bool mehrotra = false;
  std::string linear_solver = "mumps";
};

std::unique_ptr<RelaxationSolver> MakeIpoptRelaxationSolver(const IpoptSettings& settings = {});

}  // namespace mfp
