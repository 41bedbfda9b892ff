#pragma once
// Ipopt backend of RelaxationSolver. Ipopt headers stay inside the .cc file.
#include <memory>
#include <string>

#include "planner/relaxation_solver.h"

namespace mfp {

struct IpoptSettings {
  double tolerance = 1e-8;       // Ipopt "tol"
  int max_iterations = 500;      // per relaxation
  double max_cpu_time_s = 10.0;  // per relaxation
  // Mehrotra's predictor-corrector: Ipopt's recommended mode for convex QPs.
  bool mehrotra = true;
  std::string linear_solver = "mumps";
};

std::unique_ptr<RelaxationSolver> MakeIpoptRelaxationSolver(const IpoptSettings& settings = {});

}  // namespace mfp
