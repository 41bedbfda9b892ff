#pragma once
// The surface a sensor saw from above, carried beside the regions made from it. Regions
// are where the planner may put a foot; the seen surface is where a robot may already be
// standing: a start foot on it is a fact the planner accepts even where the regions, inset
// and cut around sensor noise, leave it out. Plain Eigen.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "geometry/convex_region.h"

namespace mfp {

// One single-valued layer of seen surface on a regular grid (a voxel map's surface layer
// or a height map): cell (row, col) spans origin + [col, col + 1) x [row, row + 1) cells.
struct SurfaceGrid {
  double resolution_m = 0.0;                           // cell edge [m]
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // lower corner of cell (0, 0) [m, world]
  int rows = 0;                                        // cells along y
  int cols = 0;                                        // cells along x
  // Row-major (row = y index): the surface's top (a voxel's top face) [m]; NaN = nothing
  // seen from above with room above it.
  std::vector<float> height_m;
};

struct SeenSurface {
  std::vector<SurfaceGrid> grids;    // the layers of a map
  std::vector<ConvexRegion> faces;   // exact faces (a box terrain's top faces, uninset)
  bool empty() const { return grids.empty() && faces.empty(); }
};

// True when the point lies on the seen surface within tolerance_m: in plan view within
// tolerance_m of a seen cell (or face), and in height within tolerance_m of the cell's
// surface, which may lie anywhere in its top voxel (a cell's top minus one cell edge).
bool OnSeenSurface(const SeenSurface& surface, const Eigen::Vector3d& point_world_m, double tolerance_m);

struct NearestSurfacePoint {
  bool found = false;
  Eigen::Vector3d point_world_m = Eigen::Vector3d::Zero();
  double distance_m = 0.0;  // 3-D distance from the query point [m]
};

// The seen surface point nearest to the query (cell centres at their tops; face points
// on their planes) within search_radius_m in plan view; found = false when none is.
NearestSurfacePoint NearestSeenSurface(const SeenSurface& surface, const Eigen::Vector3d& point_world_m,
                                       double search_radius_m);

// The highest seen surface at (x, y): the top of the cell holding it in each grid, the
// plane of each face whose polygon holds it; nullopt when none does [m].
std::optional<double> HighestSeenSurfaceAt(const SeenSurface& surface, const Eigen::Vector2d& xy_m);

// The lowest and highest tops of a disk of seen surface, and the cell edge of its grid [m].
struct SeenDisk {
  double low_m = 0.0;
  double high_m = 0.0;
  double cell_m = 0.0;
};

// A disk of one grid's seen surface, flat within a cell: every cell of the grid whose
// square comes closer than radius_m plus one cell edge (the edges' uncertainty) to xy_m
// in plan view is seen (a finite top), and those
// tops lie within one cell edge of each other (a surface's top voxel, not a step). Two
// levels a cell apart are sensor noise when the scarcer level's cells are scattered (pits
// and bumps of one voxel); a riser or curb one voxel high is a run of them, 4-connected
// cells at least three cells and radius_m long, and the disk is not flat. The first grid
// (layer) that holds such a disk answers; nullopt when none does. Faces are not searched
// (their regions are exact).
// refuse_runs = false keeps the older test (two levels a cell apart pass, runs or not): for a
// disk about a foot already standing there.
std::optional<SeenDisk> FlatSeenDisk(const SeenSurface& surface, const Eigen::Vector2d& xy_m, double radius_m,
                                     bool refuse_runs = true);

}  // namespace mfp
