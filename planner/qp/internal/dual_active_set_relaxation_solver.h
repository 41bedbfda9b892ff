#pragma once
// The dual active-set method (dual_active_set_qp.h) as a RelaxationSolver. Each solver
// object keeps its own factors, so each branch-and-bound worker warm-starts from the
// last node it solved.
#include <memory>

#include "planner/qp/dual_active_set_qp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

std::unique_ptr<RelaxationSolver> MakeDualActiveSetRelaxationSolver(const DualActiveSetOptions& options = {});

}  // namespace mfp
