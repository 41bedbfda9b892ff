#pragma once
// A RelaxationSolver that asks a fallback whenever its primary solver ends without an
// answer (the default backend: mfp's interior point, then Ipopt). A result the fallback
// gives carries RelaxationResult::fallbacks = 1 and the wall time of both attempts.
#include <memory>

#include "planner/qp/relaxation_solver.h"

namespace mfp {

std::unique_ptr<RelaxationSolver> MakeFallbackRelaxationSolver(std::unique_ptr<RelaxationSolver> primary,
                                                               std::unique_ptr<RelaxationSolver> fallback);

}  // namespace mfp
