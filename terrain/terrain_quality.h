#pragma once
// Measures extracted regions against the exact terrain they came from (a box
// description): soundness (every region point lies on a real top surface, within a
// distance in voxels) and coverage (fraction of each flat top face, inset by the foot
// radius, that some region covers). Used by the tests and by mfp-terrain-bench.
#include <string>
#include <vector>

#include "terrain/convex_region.h"
#include "terrain/terrain_description.h"

namespace mfp {

// Height of the highest box surface above (x, y), or NaN when no box is there [m].
double TrueTopHeight(const TerrainDescription& terrain, double x_m, double y_m);

// Largest distance [m] from points sampled on the regions (vertices, edges and interior)
// to the true top surface: for each point the smallest sqrt(dxy^2 + dz^2) over horizontal
// offsets dxy of up to search_radius_m. Infinity when a point is above no surface.
double MaxDistanceToTopSurfaceM(const std::vector<ConvexRegion>& regions,
                                const TerrainDescription& terrain, double search_radius_m);

struct FaceCoverage {
  int box = -1;
  std::string name;
  double slope_rad = 0.0;
  double visible_area_m2 = 0.0;  // inset face area not under or beside a higher box [m^2]
  double coverage = 0.0;         // fraction of it inside a region at the face's height
};

// For each box whose top face is no steeper than max_slope_rad and whose visible inset
// area exceeds a foot's area (pi r^2): the fraction covered by regions whose plane lies
// within height_tolerance_m of the face.
std::vector<FaceCoverage> TopFaceCoverage(const std::vector<ConvexRegion>& regions,
                                          const TerrainDescription& terrain,
                                          double foot_radius_m, double max_slope_rad,
                                          double height_tolerance_m);

}  // namespace mfp
