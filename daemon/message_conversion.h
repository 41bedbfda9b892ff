#pragma once
// Planner types to outgoing LCM messages and back (tools read replies with FromPlanMessage).
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "mfp/plan_t.hpp"
#include "mfp/region_set_t.hpp"
#include "planner/formulation/plan.h"

namespace mfp {

// plan_t for a request; utime and map_utime are the caller's.
plan_t ToPlanMessage(const Plan& plan, int64_t request_id, const std::string& robot_name,
                     int64_t utime, int64_t map_utime);

// A reply without footsteps (rejected or dropped request).
plan_t StatusReply(SolveStatus status, const std::string& message, int64_t request_id,
                   const std::string& robot_name, int64_t utime, int64_t map_utime);

region_set_t ToRegionSetMessage(const std::vector<ConvexRegion>& regions, const std::string& frame,
                                int64_t utime, int64_t map_utime);

// Regions back from a region_set_t (for tools and tests that check plans).
std::vector<ConvexRegion> FromRegionSetMessage(const region_set_t& message);

// Footsteps back from a plan_t.
std::vector<Footstep> FootstepsFromPlanMessage(const plan_t& message);

}  // namespace mfp
