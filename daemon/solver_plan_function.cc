#include "daemon/solver_plan_function.h"

#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {

PlanFunction MakeSolverPlanFunction() {
  return [](const RobotModel& robot, const std::vector<ConvexRegion>& regions,
            const PlanRequest& request, const PlannerOptions& options) {
    // One solver per plan: plans run one at a time and solver set-up is cheap next to
    // a solve; no state leaks from one request into the next.
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
    return PlanFootsteps(robot, regions, request, options, solvers.workers());
  };
}

}  // namespace mfp
