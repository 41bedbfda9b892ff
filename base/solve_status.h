#pragma once
#include <string>

namespace mfp {

// Outcome of a planning or solver call. Numeric values are part of the LCM contract
// (plan_t.status mirrors them), so append new values, never renumber.
enum class SolveStatus : int {
  kOptimal = 0,          // proven optimal within the gap tolerance
  kFeasible = 1,         // feasible plan, optimality not proven (node limit, heuristic, or
                         // every node explored but the certified floors short of the gap)
  kTimeLimit = 2,        // time limit hit; best plan found so far is returned
  kInfeasible = 3,       // proven: no assignment satisfies the constraints
  kInvalidRequest = 4,   // malformed request (NaN, wrong leg count, limits exceeded, ...)
  kNoMap = 5,            // no terrain regions known yet
  kInvalidStart = 6,     // start stance off every region
  kInvalidGoal = 7,      // goal off every region
  kInternalError = 8,    // a solver failed in a way that is not the input's fault
  kNoSolution = 9,       // limits hit before any feasible plan was found
  kDropped = 10,         // request dropped from a full queue, or the daemon stopping
  kSuperseded = 11,      // a newer request from the same client replaced it in the queue
  kPartial = 12,         // a valid plan that stops short of the goal (step budget, time
                         // limit or no further window found); safe to execute, message says
                         // how far it got and why
  kNoRoute = 13,         // no route: the regions' graph under the robot's reach and height
                         // limits does not connect the start to the goal; message names
                         // where the route breaks
};

// Lower-case name used in JSON ("optimal", "time_limit", ...).
std::string ToString(SolveStatus status);

// True when the status carries a usable plan.
bool HasPlan(SolveStatus status);

}  // namespace mfp
