#include "base/solve_status.h"

#include "base/check.h"

namespace mfp {

std::string ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kOptimal: return "optimal";
    case SolveStatus::kFeasible: return "feasible";
    case SolveStatus::kTimeLimit: return "time_limit";
    case SolveStatus::kInfeasible: return "infeasible";
    case SolveStatus::kInvalidRequest: return "invalid_request";
    case SolveStatus::kNoMap: return "no_map";
    case SolveStatus::kInvalidStart: return "invalid_start";
    case SolveStatus::kInvalidGoal: return "invalid_goal";
    case SolveStatus::kInternalError: return "internal_error";
    case SolveStatus::kNoSolution: return "no_solution";
    case SolveStatus::kDropped: return "dropped";
    case SolveStatus::kSuperseded: return "superseded";
    case SolveStatus::kPartial: return "partial";
    case SolveStatus::kNoRoute: return "no_route";
  }
  MFP_CHECK_MSG(false, "unknown SolveStatus " + std::to_string(static_cast<int>(status)));
}

bool HasPlan(SolveStatus status) {
  return status == SolveStatus::kOptimal || status == SolveStatus::kFeasible ||
         status == SolveStatus::kTimeLimit || status == SolveStatus::kPartial;
}

}  // namespace mfp
