#pragma once
// Decomposes one planar patch into convex polygons of safe foot-centre positions.
//
// Soundness argument (why the polygons hold only walkable surface): the patch's surface
// S is the union of its cells' squares. A cell is kept ("eroded mask") when every cell
// whose square comes closer than the inset to the cell's centre belongs to the patch, so
// a foot disk centred on a kept cell's centre lies in S. For any point inside the square
// spanned by four kept centres, each cell its disk touches is also touched by the disk of
// the corner nearest to that cell, axis by axis; so the whole square is safe. The union of
// such complete "dual" squares is covered by rectangles - on the grid itself, or on a
// grid rotated into the patch's principal frame whose cells are kept only when their
// bounding box lies in complete dual squares. The argument holds cell by cell, so each
// outside cell may ask its own inset (a drop beside the patch more than a wall).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "terrain/extraction/cell_fate.h"
#include "terrain/extraction/height_map.h"
#include "terrain/extraction/internal/convex_cover.h"
#include "terrain/extraction/internal/plane_segmentation.h"
#include "terrain/extraction/internal/rectangle_cover.h"

namespace mfp {

struct PatchDecompositionOptions {
  double inset_m = 0.0;             // kept from every cell outside the patch [m]
  // Kept in addition from cells outside the patch, next to it, where its surface may end
  // inside its own boundary cell (the map's edge uncertainty) [m]: every such cell unless
  // solid_beside says material rises there from the surface's level (then riser_inset_m).
  double drop_inset_m = 0.0;
  // Kept in addition from cells next to the patch where material rises from its level
  // (a wall or riser may reach into the patch's boundary cell by this much) [m].
  double riser_inset_m = 0.0;
  // Per height map cell, SurfaceLayers::solid_beside bits of the patch's layer; nullptr:
  // every neighbour is a possible drop.
  const std::vector<uint8_t>* solid_beside = nullptr;
  // Per height map cell, SurfaceLayers::filled of the patch's layer; nullptr: none. An
  // erased fill (kFilledErased) is left out of the patch's cells and keeps inset_m alone
  // from foot centres: its 8 neighbours are seen floor of one height, so no edge
  // uncertainty is added, but no foot disk may reach the cell the sensor did not see.
  const std::vector<uint8_t>* filled = nullptr;
  double min_area_xy_m2 = 0.0;      // smallest rectangle kept, projected on x-y [m^2]
  double axis_snap_rad = 0.05;      // principal frames this close to the grid use the grid
  RectangleCoverOptions cover;      // min_rect_cells is derived from min_area_xy_m2
  // Cover the complete dual squares by convex pieces grown along their outline
  // (convex_cover.h) instead of rectangles on the grid or the principal frame.
  bool convex_pieces = false;
  int max_piece_vertices = 8;       // vertices of a convex piece at most
  bool shrunk_seeds = true;         // ConvexCoverOptions::shrunk_seeds
  int shrunk_seed_min_cells = 1;    // ConvexCoverOptions::shrunk_seed_min_cells
  // With convex_pieces: a patch with at least this many kept cells and a ragged outline
  // (below) is covered by the pieces alone (no rectangles to compare them with); the
  // default: every patch compares.
  int convex_alone_cells = std::numeric_limits<int>::max();
  double convex_alone_outline = 2.5;         // RegionExtractorOptions::convex_alone_outline
  double convex_alone_outline_share = 0.1;   // RegionExtractorOptions::convex_alone_outline_share
  // A convex piece narrower than this (its width: the least distance between two parallel
  // lines enclosing it) is dropped unless it is the patch's first [m]: slivers along a
  // ragged outline add little floor and many regions for the planner to choose among.
  double min_piece_width_m = 0.0;
};

using Quad2d = std::array<Eigen::Vector2d, 4>;  // counter-clockwise x-y corners [m, world]

// The regions: counter-clockwise convex polygons in x-y [m, world] (quads unless
// convex_pieces). fates (optional): per patch cell (in patch.cells' order), what the decomposition did
// with it - kInsetOffPatch, kInsetBeyond, kUncovered or kCovered (all kSmallPatch when
// the patch is too thin to decompose). The certification radius of kInsetOffPatch is
// inset_m + drop_inset_m, centre to centre. pieces_alone (optional): whether the regions
// are the convex pieces alone, the rectangles not computed (convex_alone_cells).
std::vector<Polygon2d> DecomposePatch(const HeightMap& height_map, const PlanarPatch& patch,
                                   const PatchDecompositionOptions& options, std::vector<CellFate>* fates = nullptr,
                                   bool* pieces_alone = nullptr);

// Angle in [0, pi/2) of the smallest-area bounding rectangle of the patch's cells.
double PrincipalAngleRad(const HeightMap& height_map, const PlanarPatch& patch);

}  // namespace mfp
