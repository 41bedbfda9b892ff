#include "tools/daemon/ipopt_plan_function.h"

#include "planner/ipopt_relaxation_solver.h"

namespace mfp {

PlanFunction MakeIpoptPlanFunction() {
  return [](const RobotModel& robot, const std::vector<ConvexRegion>& regions,
            const PlanRequest& request, const PlannerOptions& options) {
    // One solver per plan: plans run one at a time and solver set-up is cheap next to
    // a solve; no state leaks from one request into the next.
    const std::unique_ptr<RelaxationSolver> solver = MakeIpoptRelaxationSolver();
    return PlanFootsteps(robot, regions, request, options, *solver);
  };
}

}  // namespace mfp
