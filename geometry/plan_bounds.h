#pragma once
// The plan-view (x, y) bounding box of a convex region: the cheap first test of code that
// asks which regions lie near a point, a path or another region.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/convex_region.h"

namespace mfp {

// The smallest closed box holding every vertex of the region's polygon in plan view
// [m, world]; empty (isEmpty()) when the region has no vertices.
Eigen::AlignedBox2d PlanBounds(const ConvexRegion& region);

}  // namespace mfp
