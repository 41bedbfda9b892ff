#pragma once
// Measures extracted regions against the exact terrain they came from (a box
// description): soundness (every region point lies on a real top surface, within a
// distance in voxels) and coverage (fraction of each flat top face, inset by the foot
// radius, that some region covers). Used by the tests and by mfp-terrain-bench.
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "geometry/terrain_description.h"

namespace mfp {

// Height of the highest box surface above (x, y), or NaN when no box is there [m].
double TrueTopHeight(const TerrainDescription& terrain, double x_m, double y_m);

// Height of the first box surface met going down from (x, y, z_from), or NaN when there
// is none or (x, y, z_from) lies inside a box [m]. Sees floors under tables and bridges.
double TrueSurfaceBelow(const TerrainDescription& terrain, double x_m, double y_m, double z_from_m);

// The truth test for a foot centre: true when the disk of radius radius_m about
// point_world_m, on the plane through it with upward normal normal_world, lies on real
// top surface - at every sample q of the disk (centre, and rings every radius / 2), the
// first surface below q + height_tolerance_m is within height_tolerance_m of q (and q +
// height_tolerance_m is not inside a box). A foot centre with radius = foot radius +
// edge margin passing this has at least the margin of real surface around its foot.
bool OnTrueTopSurface(const TerrainDescription& terrain, const Eigen::Vector3d& point_world_m,
                      double radius_m, double height_tolerance_m,
                      const Eigen::Vector3d& normal_world = Eigen::Vector3d::UnitZ());

// The truth test for a planned foot on a course of boxes (bench/course_checker.h, the
// course generator): true when a foot centred at p stands on the top face of a box no
// steeper than max_slope_rad, within height_tol_m of it, and the disk of radius margin_m
// about p on that face's plane lies on real top surface (OnTrueTopSurface): faces that
// abut within height_tol_m of each other count as one surface, a drop, gap or solid
// above within the margin fails.
bool FootOnTrueSurface(const TerrainDescription& terrain, const Eigen::Vector3d& p, double margin_m,
                       double max_slope_rad, double height_tol_m);

struct RegionSoundness {
  int samples = 0;        // points sampled on the regions (vertices, edges, interior)
  int sound = 0;          // of them, passing OnTrueTopSurface
  double fraction = 1.0;  // sound / samples (1 when there are no regions)
  Eigen::Vector3d worst_point = Eigen::Vector3d::Zero();  // a failing sample, if any
};

// Soundness of regions against the true geometry: the share of sampled region points
// whose disk of radius radius_m (foot radius + edge margin) lies on a true top surface.
RegionSoundness MeasureSoundness(const std::vector<ConvexRegion>& regions,
                                 const TerrainDescription& terrain, double radius_m,
                                 double height_tolerance_m);

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

struct CoverageOptions {
  double inset_m = 0.0;          // the walkable part of a face: inset by this [m]
  double disk_radius_m = 0.0;    // a point is visible when this disk about it has room above
  double clearance_m = 1e9;      // room needed above a face point (no box within) [m]
  double max_slope_rad = 0.45;
  double height_tolerance_m = 0.0;  // a region covers a point when its plane is this close
  std::string only_face;            // when set, only the box of this name is measured
};

// The same with the walkable part and room above stated: floors under tables and bridges
// count where they have the clearance above them.
std::vector<FaceCoverage> TopFaceCoverage(const std::vector<ConvexRegion>& regions,
                                          const TerrainDescription& terrain,
                                          const CoverageOptions& options);

}  // namespace mfp
