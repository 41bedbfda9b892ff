#pragma once
// From an occupancy map to the planner's safe regions (the paper's "obstacle-free convex
// regions"): surfaces with room above them, stacked into single-valued layers
// (surface_layers.h) -> per layer, local plane fits -> planar patches -> each patch inset
// by the foot radius, the map's edge uncertainty and an edge margin, and covered by large
// rectangles (in the patch's principal frame) that hold only walkable surface ->
// ConvexRegion (edges plus the plane as two inequalities, a tolerance from the voxel size
// apart). Plain Eigen; one entry point with Options / Result types.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "geometry/terrain_description.h"
#include "terrain/extraction/cell_fate.h"
#include "terrain/extraction/height_map.h"
#include "terrain/extraction/internal/surface_layers.h"
#include "terrain/extraction/map_body_obstacles.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

struct RegionExtractorOptions {
  double foot_radius_m = 0.01;     // regions hold foot centres whose whole disk is on the patch [m]
  // Real surface kept around the foot's disk, beyond the foot radius [m].
  double edge_margin_m = 0.01;
  // How far inside the outermost occupied voxel the true edge may lie, in voxels: a
  // sensor marks a voxel occupied when any point of it is hit, so up to one voxel. Added
  // only beside drops and unseen space: where material rises beside a surface (a wall, a
  // riser; SurfaceLayers::solid_beside) the surface runs on to it.
  double edge_uncertainty_voxels = 1.0;
  // How far a wall or riser beside a surface may reach into the surface's outermost
  // voxel, in voxels: 0 for maps whose voxels are occupied when any point is hit (the
  // voxel above the surface would be occupied), half a voxel for voxelisations that mark
  // a voxel when its centre is inside. The default suits either kind of map.
  double riser_uncertainty_voxels = 0.5;
  // Free space a surface needs above it [m] (the robot's stance height plus a margin,
  // from the planner). Infinity: only the highest surface of each column.
  double clearance_m = std::numeric_limits<double>::infinity();
  // In maps that store free space, a surface must have been seen from above.
  bool require_seen_from_above = true;
  // In maps that store free space: unseen floor enclosed by seen floor of one height
  // within this many cells along all 8 grid directions is floor
  // (SurfaceLayerOptions::enclosed_unseen_radius_cells; docs/unseen_floor.md). 0: off.
  int enclosed_unseen_radius_cells = 3;
  double max_slope_rad = 0.45;     // steeper patches are rejected [rad]
  double min_region_area_m2 = 0.0016;  // smaller regions (of foot centres) are dropped [m^2]
  // ... but never more than this many voxels' area (0: min_region_area_m2 alone). Every
  // region is inset by the foot, the margin and the edge uncertainty: however small, its
  // foot centres are footholds, and on a fine map stepping stones with a few centimetres
  // to spare keep their regions (the 16 cm^2 default alone dropped most of them).
  double min_region_area_voxels = 1.0;
  // Tolerances in voxels (multiples of the map resolution), since the voxel size is
  // what limits how well a surface is known.
  double grow_tolerance_voxels = 1.0;   // a cell joins a patch within this of its plane
  double max_residual_voxels = 0.75;    // patch cells further from the final plane are dropped
  // Sensor noise on a surface (a real floor's top voxel jumps by a voxel): a group of at
  // most noise_max_cells 4-connected cells, each within noise_tolerance_voxels of its
  // patch's plane or unseen floor (SurfaceLayers::unseen), enclosed on all 8 sides by the
  // patch's own cells, stays in the patch instead of being cut out and inset by the foot
  // and margin. A longer run (a riser) or a group at the patch's edge is a real edge; a
  // cell further off (a deeper pit) or with a lower surface seen below is a drop.
  // The same groups off their 3 x 3 neighbourhood's median are grown at that median, and
  // patches too small to hold a foot (with margin and edge uncertainty) join the surface
  // around them within noise_tolerance_voxels (noise_levels.h, noise_patches.h): a
  // scanned floor is one surface, a stone one voxel up that holds a foot stays a step.
  // noise_max_cells 0: no noise kept.
  double noise_tolerance_voxels = 1.4;
  int noise_max_cells = 4;
  double seed_roughness_voxels = 0.35;  // RMS residual of the local fit for a patch seed
  double plane_tolerance_voxels = 0.5;  // half-thickness of each region's plane slab
  double target_coverage = 0.97;        // stop covering a patch once this fraction is covered
  // A patch's cover stops at max(max_regions_per_patch, regions_per_m2 * the patch's
  // area) regions. A floor with scattered holes (every cut inset by the foot) needs
  // regions in proportion to its area: a fixed 24 left a quarter of a scanned room's
  // certifiable floor uncovered (docs/measurements.md, "Where the seen floor goes"). At 4
  // per m^2 the scanned lab's floor (fr_079) stopped at its cap with 9 % of its
  // certifiable floor uncovered; 5 covers it past 85 % and changes no other scan or
  // simulated map (docs/measurements.md, "Extraction time round 5").
  int max_regions_per_patch = 24;
  double regions_per_m2 = 5.0;
  // Rectangles of one patch may overlap (each grown over cells others cover). Off: they
  // only share sides, so a foothold inside a patch has one region, not several equivalent
  // ones for the branch-and-bound to tell apart (ANYmal C down the scanned corridor:
  // 1.6 s with all 17 windows proven, against 33 s with 3 windows at the node cap).
  bool overlapping_regions = false;
  // A patch's certified cells are covered by convex pieces grown along their outline
  // (diagonals between holes, chords of a ring; convex_cover.h), each side then moved out
  // to the exact inset as the rectangles' are, instead of rectangles on the grid or the
  // patch's principal frame; each piece has at most max_region_vertices vertices (rows
  // for the planner per region), and a piece narrower than foot_radius_m is dropped
  // unless it is its patch's first; kept per patch only where they hold more kept cells'
  // centres than the rectangles (computed only where the rectangles leave room for that),
  // or alone on a patch of convex_alone_cells kept cells or more.
  // On by default (docs/measurements.md, "The convex pieces cheap enough to
  // be the default"); off: the rectangles everywhere.
  bool convex_cover = true;
  int max_region_vertices = 8;
  // With convex_cover, a patch with at least convex_alone_cells kept cells (cells whose
  // centre holds a foot disk) and a ragged outline - kept cells with a 4-neighbour not
  // kept numbering at least convex_alone_outline times a square's outline of as many
  // cells (4 sqrt(kept)) and convex_alone_outline_share of the kept cells - is covered by
  // the convex pieces alone: the rectangles, computed only to compare, are not. On large
  // ragged patches the pieces nearly always win the comparison, so computing the
  // rectangles there is wasted work; smooth outlines (faces of boxes, a flat floor)
  // compare as before (figures: docs/measurements.md, "Extraction time round 7"). A value
  // of convex_alone_cells above any patch: every patch compares.
  int convex_alone_cells = 400;
  double convex_alone_outline = 2.5;
  double convex_alone_outline_share = 0.1;
  // With convex_cover, each piece is grown about its seed rectangle and about the seed's
  // middle half and quarter, the best kept (true), or about the seed alone (false: a
  // third of the growing, but less certified coverage and a curved walkway's pieces no
  // better than rectangles; figures: docs/measurements.md, "Extraction time round 7").
  bool convex_shrunk_seeds = true;
  // ... the middle half and quarter of a seed at least this many cells on its shorter side
  // only: a thinner seed shrinks along its length alone, and its middle part grows nearly
  // the same piece, so on a scan's ragged floor most of that growing is wasted (figures:
  // docs/measurements.md, "Extraction time round 8"). 1: every seed.
  int convex_shrunk_seed_min_cells = 2;
  // At most this many regions, the largest patches first (a bound on the work of the
  // planners that read them). 256 dropped half the cells of an uneven field of 387 blocks,
  // footholds the route needed: the planner answered 'no route' where one existed.
  int max_regions = 4096;
  double axis_snap_rad = 0.05;          // a patch within this of the grid axes uses the grid
  size_t max_height_map_cells = kDefaultMaxHeightMapCells;
  // Most neighbour visits of the surface fit, (surface cells) * (2 w + 1)^2 with w the
  // foot radius in cells: a map much finer than the foot (0.1 mm cells for a 1 cm foot:
  // 201^2 visits per cell) is refused up front, naming its resolution, instead of taking
  // minutes. About 1e8 visits a second on one core; a 4096^2-cell map at w = 1 is 1.5e8.
  double max_fit_work = 3e8;
  // Record what became of every surface cell (RegionExtractionResult::cell_fates): a
  // diagnostic for benches, off by default.
  bool record_cell_fates = false;
  // Threads of the surface fit, the segmentation and the decomposition (each layer's fit
  // and patches, each patch's regions are independent): the calling thread and
  // threads - 1 more, joined before ExtractRegions returns. The regions do not depend on
  // it. 2 suits a two-core onboard computer; 1 keeps the extraction on the calling thread.
  int threads = 2;
  // Ends the extraction (checked every height map row and every patch): the regions of
  // the patches done so far are returned, with a message saying the time ran out.
  Deadline deadline;
  // When set, ExtractRegions also finds the body's obstacles in the map
  // (map_body_obstacles.h; its deadline is this one).
  std::optional<MapObstacleOptions> body_obstacles;
};

struct RegionExtractionStats {
  int surface_cells = 0;       // surfaces in all layers
  int layers = 0;              // single-valued surface layers (1 without overlapping levels)
  int no_room_above = 0;       // surfaces rejected: occupied voxel within the clearance
  int not_seen_from_above = 0; // surfaces rejected: top voxel not known free
  int isolated_voxels = 0;     // single outlier voxels ignored
  int patches = 0;             // planar patches found
  int patches_too_steep = 0;   // rejected: slope above max_slope_rad
  int patches_too_small = 0;   // rejected: smaller than a foot, or nothing left after the inset
  int patches_convex_alone = 0;  // covered by the convex pieces alone (convex_alone_cells), no rectangles computed
  double height_map_s = 0.0;   // wall time per stage [s]
  double analysis_s = 0.0;
  double segmentation_s = 0.0;
  double decomposition_s = 0.0;
  double total_s = 0.0;
};

struct RegionExtractionResult {
  std::vector<ConvexRegion> regions;  // ids 0, 1, ... in order
  RegionExtractionStats stats;
  HeightMap height_map;               // layer 0, for display
  std::vector<HeightMap> layers;      // every surface layer (mfp-regions --svg shows them apart)
  std::vector<int> region_layer;      // per region, the layer it lies on
  // Cells whose seen height the noise repair moved, at that seen height (SurfaceLayers::
  // moved_as_seen): with `layers`, the surface the map saw from above.
  std::vector<HeightMap> moved_as_seen;
  // Per layer and cell, what the extractor filled and why (SurfaceLayers::filled): no
  // region comes within the foot radius and the edge margin of an erased fill, and the
  // seen surface leaves it out (SeenSurfaceOfLayers). Empty when not computed.
  std::vector<std::vector<uint8_t>> filled;
  // With record_cell_fates: per layer and height map cell, a CellFate (cell_fate.h).
  std::vector<std::vector<CellFate>> cell_fates;
  std::string message;                // why there are no regions, when there are none
  bool stopped = false;               // the deadline ended it early (message says where)
  // With RegionExtractorOptions::body_obstacles, from an occupancy map (not a height map).
  std::optional<MapObstacles> body_obstacles;
};

// Every region point f keeps a disk of radius foot_radius_m + edge_margin_m on the map's
// surface cells shrunk by edge_uncertainty_voxels at their drops. Throws InputError on options out of
// range (foot radius not in [0, 1] m, max slope not in (0, pi/2), tolerances not
// positive, clearance not > 0) and on maps BuildHeightMap rejects.
RegionExtractionResult ExtractRegions(const OccupancyMap& map,
                                      const RegionExtractorOptions& options);

// The same stages from surface layers made elsewhere (a height map: height_grid.h): the
// surface fit, planar patches and decomposition. Every layer shares one grid and has its
// solid_beside bits; `candidates` counts the surface cells. Throws InputError on options
// out of range, as ExtractRegions does. (Clearance and seen-from-above options do not apply.)
RegionExtractionResult ExtractRegionsFromLayers(SurfaceLayers layers,
                                                const RegionExtractorOptions& options);

// Makes the map of a box description (MakeTerrainMap: voxelised, or scanned from its
// sensors, with its noise) and extracts its regions: what a scenario with a `terrain:`
// block plans on. A plain voxelisation (no scan, no noise) is known to put true edges
// within half a voxel of its cells, so its edge uncertainty is at most 0.5 voxels.
RegionExtractionResult ExtractRegionsFromTerrain(const TerrainDescription& terrain,
                                                 const RegionExtractorOptions& options);

}  // namespace mfp
