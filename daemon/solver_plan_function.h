#pragma once
// The real PlanFunction: PlanFootsteps with the relaxation backend the options name.
#include "daemon/daemon_core.h"

namespace mfp {

PlanFunction MakeSolverPlanFunction();

}  // namespace mfp
