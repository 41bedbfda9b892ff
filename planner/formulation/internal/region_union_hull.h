#pragma once
// The convex hull of a set of regions seen from above: the smallest convex polygon (as
// half-planes a . (x, y) <= b) holding every region's vertices, and the height range of
// the regions' slabs. A foot that stands on one of the regions stands in this hull; the
// converse does not hold (the hull covers the gaps between them), so it is a relaxation
// of the choice among the regions.
#include <Eigen/Core>
#include <vector>

#include "geometry/convex_region.h"

namespace mfp {

struct RegionUnionHull {
  Eigen::Matrix<double, Eigen::Dynamic, 2> A;  // one row per edge, outward unit normal
  Eigen::VectorXd b;                           // [m]
  double z_lower_m = 0.0, z_upper_m = 0.0;     // lowest and highest slab height [m]
};

// regions must be non-empty. Collinear and duplicate vertices add no edge; a hull of
// fewer than 3 distinct points (degenerate regions) yields the rows of its segment or
// point (two opposite half-planes per direction), so the result is always bounded.
RegionUnionHull HullOfRegions(const std::vector<const ConvexRegion*>& regions);

}  // namespace mfp
