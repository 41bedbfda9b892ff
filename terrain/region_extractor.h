#pragma once
// From an occupancy map to the planner's safe regions (the paper's "obstacle-free convex
// regions"): height map of top surfaces -> local plane fits -> planar patches -> each patch
// inset by the foot radius and covered by large rectangles (in the patch's principal
// frame) that hold only walkable surface -> ConvexRegion (edges plus the plane as two
// inequalities, a tolerance from the voxel size apart). Plain Eigen; one entry point with
// Options / Result types.
#include <cstddef>
#include <string>
#include <vector>

#include "terrain/convex_region.h"
#include "terrain/height_map.h"
#include "terrain/occupancy_map.h"
#include "terrain/terrain_description.h"

namespace mfp {

struct RegionExtractorOptions {
  double foot_radius_m = 0.01;     // regions hold foot centres whose whole disk is on the patch [m]
  double max_slope_rad = 0.45;     // steeper patches are rejected [rad]
  double min_region_area_m2 = 0.0016;  // smaller regions (of foot centres) are dropped [m^2]
  // Tolerances in voxels (multiples of the map resolution), since the voxel size is
  // what limits how well a surface is known.
  double grow_tolerance_voxels = 1.0;   // a cell joins a patch within this of its plane
  double max_residual_voxels = 0.75;    // patch cells further from the final plane are dropped
  double seed_roughness_voxels = 0.35;  // RMS residual of the local fit for a patch seed
  double plane_tolerance_voxels = 0.5;  // half-thickness of each region's plane slab
  double target_coverage = 0.97;        // stop covering a patch once this fraction is covered
  int max_regions_per_patch = 24;
  int max_regions = 256;                // the largest patches are kept first
  double axis_snap_rad = 0.05;          // a patch within this of the grid axes uses the grid
  size_t max_height_map_cells = kDefaultMaxHeightMapCells;
  // Most neighbour visits of the surface fit, (surface cells) * (2 w + 1)^2 with w the
  // foot radius in cells: a map much finer than the foot (0.1 mm cells for a 1 cm foot:
  // 201^2 visits per cell) is refused up front, naming its resolution, instead of taking
  // minutes. About 1e8 visits a second on one core; a 4096^2-cell map at w = 1 is 1.5e8.
  double max_fit_work = 3e8;
  // Ends the extraction (checked every height map row and every patch): the regions of
  // the patches done so far are returned, with a message saying the time ran out.
  Deadline deadline;
};

struct RegionExtractionStats {
  int surface_cells = 0;       // height map cells with a surface
  int patches = 0;             // planar patches found
  int patches_too_steep = 0;   // rejected: slope above max_slope_rad
  int patches_too_small = 0;   // rejected: smaller than a foot, or nothing left after the inset
  double height_map_s = 0.0;   // wall time per stage [s]
  double analysis_s = 0.0;
  double segmentation_s = 0.0;
  double decomposition_s = 0.0;
  double total_s = 0.0;
};

struct RegionExtractionResult {
  std::vector<ConvexRegion> regions;  // ids 0, 1, ... in order
  RegionExtractionStats stats;
  HeightMap height_map;               // for display (mfp-regions --svg)
  std::string message;                // why there are no regions, when there are none
  bool stopped = false;               // the deadline ended it early (message says where)
};

// Throws InputError on options out of range (foot radius not in [0, 1] m, max slope not in
// (0, pi/2), tolerances not positive) and on maps BuildHeightMap rejects.
RegionExtractionResult ExtractRegions(const OccupancyMap& map,
                                      const RegionExtractorOptions& options);

// Voxelises a box description at its resolution and extracts its regions: what a
// scenario with a `terrain:` block plans on.
RegionExtractionResult ExtractRegionsFromTerrain(const TerrainDescription& terrain,
                                                 const RegionExtractorOptions& options);

}  // namespace mfp
