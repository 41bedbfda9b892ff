#pragma once
// The real PlanFunction: PlanFootsteps with an Ipopt relaxation solver.
#include "tools/daemon/daemon_core.h"

namespace mfp {

PlanFunction MakeIpoptPlanFunction();

}  // namespace mfp
