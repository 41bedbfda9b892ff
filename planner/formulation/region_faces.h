#pragma once
// The faces of a safe region as limits on one step (seed paper): with H_ir the binary
// choosing region r for step i,
//   H_ir => a_k . f_i <= b_k   for each face k of A_r f <= b_r
// written once through a StepEncoder: the MIQP's big-M rows (region_choice.h, big-M
// encoding) and the polisher's rows for the region its MIQP point chose.
#include "geometry/convex_region.h"
#include "planner/formulation/step_encoder.h"
#include "planner/formulation/workspace_box.h"

namespace mfp {

// indicator: H_ir; box: the footstep variables' box, over which each face's big-M is taken.
void AddRegionFaces(StepEncoder& e, const ConvexRegion& region, int i, int indicator, const Box3& box);

}  // namespace mfp
