#pragma once
// The dual active-set method (dual_active_set_qp.h) as a RelaxationSolver for
// branch-and-bound nodes, started from the parent's active set (the request's
// warm_token), with `interior` (the interior point) for every solve without one: the
// root and each relax-and-fix stage's first node (their answers' active sets, read by
// complementarity, become their children's tokens: no cold dual solves), the QPs whose
// integers are all fixed (the heuristics' roundings), and any node the dual method does
// not finish (it reports infeasibility only with a certificate checked in the data). Each solver object keeps its own
// factors: each branch-and-bound worker rebuilds from the states it solved last.
#include <memory>

#include "planner/qp/dual_active_set_qp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

std::unique_ptr<RelaxationSolver> MakeDualActiveSetRelaxationSolver(std::unique_ptr<RelaxationSolver> interior,
                                                                    const DualActiveSetOptions& options = {});

}  // namespace mfp
