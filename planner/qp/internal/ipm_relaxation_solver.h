#pragma once
// mfp's own RelaxationSolver: fixed variables removed, then the elastic interior-point
// method of interior_point_qp.h. Plain Eigen.
#include <memory>

#include "planner/qp/dual_active_set_qp.h"
#include "planner/qp/interior_point_qp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

// RelaxationRequest::certify_floor: the crossover is tried once at the interior point's
// convergence; when it does not finish, the dense dual active-set method is started from
// the active set of the interior point's answer (DualActiveSetQp::SolveFrom), and the
// higher of the two certified floors is kept. Its floor holds for any multipliers the
// method ends with (dual_active_set_qp.h), less its regularisation's worst case over the
// node's box: hence a regularisation far below the node solver's, as this runs on a
// handful of QPs per search rather than on every node. The dense method's size limit
// (max_variables) is the node solver's: its factorisation is O(n^3) before the deadline
// can stop it, so larger QPs keep the crossover's floor or the interior point's.
struct FloorCertificationOptions {
  DualActiveSetOptions active_set = [] {
    DualActiveSetOptions o;
    o.regularisation = 1e-8;
    o.max_warm_steps_per_variable = 8.0;  // an interior point's active set is a rougher start than a parent's
    o.snapshots = 1;                      // one solve per object
    return o;
  }();
};

std::unique_ptr<RelaxationSolver> MakeInteriorPointRelaxationSolver(
    const InteriorPointOptions& options = {}, const FloorCertificationOptions& certification = {});

}  // namespace mfp
