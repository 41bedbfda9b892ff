#pragma once
// Accepted footsteps become the next window's start stance, a constant of its MIQP. A
// window that keeps a foot where it stands (a trimmed step) then needs that constant to
// meet its region's rows exactly, while the relaxation solver returned it only to its
// tolerance (1e-8 m outside is common): every plan that stands still with that foot
// becomes infeasible, and a window that cannot make all its steps reports 'infeasible'.
// Snapping each accepted foot a hair inside its region removes that. No I/O.
#include <Eigen/Core>
#include <vector>

#include "terrain/convex_region.h"

namespace mfp {

// The point on the segment from p toward the region's vertex centroid nearest to p where
// every row of A f <= b holds with inside_m to spare (scaled by the row's norm); p itself
// when it already does. The move is as small as the violation (a solver tolerance).
Eigen::Vector3d SnapIntoRegion(const ConvexRegion& region, const Eigen::Vector3d& p, double inside_m);

// The region of `regions` whose id is region_id, or null.
const ConvexRegion* RegionWithId(const std::vector<ConvexRegion>& regions, int region_id);

}  // namespace mfp
