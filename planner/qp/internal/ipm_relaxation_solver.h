#pragma once
// mfp's own RelaxationSolver: fixed variables removed, then the elastic interior-point
// method of interior_point_qp.h. Plain Eigen.
#include <memory>

#include "planner/qp/interior_point_qp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

std::unique_ptr<RelaxationSolver> MakeInteriorPointRelaxationSolver(const InteriorPointOptions& options = {});

}  // namespace mfp
