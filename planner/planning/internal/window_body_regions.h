#pragma once
// The body regions of a window (FootstepProblem::body_regions, body_region_faces.h):
// convex regions of the plan free of the body obstacles that reach into the body's band
// over the window's ground, grown IRIS-style (geometry/free_region_2d.h) about the body's
// plan box at the window's start stance and at the stance route's poses ahead of it
// within the window's reach. Each region holds the box of the pose it was grown about, so
// the route's poses (clear of the obstacles) stay open to the MIQP. Private to
// planner/planning.
#include <vector>

#include "geometry/free_region_2d.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/plan_context.h"

namespace mfp {

// At most options.formulation.max_body_regions regions; empty (no body rows) when the
// option is off and the window is not `clear_of_body` (a window planned again because its
// plan took the body into an obstacle, HorizonPolicy::RetryClearOfBody), the body is
// unknown, or no obstacle in the band is near the window's regions. An obstacle counts
// when it reaches into the body's band over the highest ground the window can stand on (its start feet, and its regions no higher than its
// configurations can climb at dz_max each): walls, not the stones and steps it walks on.
std::vector<FreeRegion2d> WindowBodyRegions(const PlanContext& context, const FootstepProblem& problem,
                                           bool clear_of_body = false);

}  // namespace mfp
