#pragma once
// Every surface of an occupancy map a foot could stand on, not only the highest one per
// column: floors under tables, ground under a bridge, stair treads under an overhang.
// A surface is the top of a run of occupied voxels in a column; it is a candidate when
// the column above it holds no occupied voxel up to the robot's clearance and, in maps
// that store free space (maps built from sensor rays), the voxel on top of it is known
// free (seen from above: the top of a ceiling never is). Isolated single voxels (scan
// outliers) are ignored. Candidates are joined into sheets (neighbouring columns within
// a step gate), and the sheets are stacked into layers - single-valued height maps on
// the same grid, no two sheets of a layer sharing a column - so the height-map pipeline
// runs on each layer. Plain Eigen.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "terrain/extraction/height_map.h"
#include "terrain/extraction/leaf_budget.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

struct SurfaceLayerOptions {
  // Free space a surface needs above it [m]; the planner passes the robot's stance
  // height plus a margin. Infinity: only the highest surface of each column.
  double clearance_m = std::numeric_limits<double>::infinity();
  double step_gate_m = 0.0;           // neighbouring surfaces closer than this join a sheet [m]
  bool require_seen_from_above = true;  // applies only when the map stores free space
  bool drop_isolated_voxels = true;
  bool fill_single_cell_noise = true;   // FillSingleCellNoise on every layer
  // In maps that store free space: an unseen empty cell whose nearest surface along each
  // of the 8 grid directions is at most this many cells away, all within a voxel of one
  // height, is floor at that height (docs/unseen_floor.md). 0: off.
  int enclosed_unseen_radius_cells = 0;
  size_t max_cells = kDefaultMaxHeightMapCells;
  uint64_t max_leaf_columns = kDefaultMaxLeafColumns;  // CheckLeafColumnBudget (leaf_budget.h)
  int threads = 1;  // the layer stage's passes (grid bounds, footprints, columns, bands of rows) on this many (parallel_work.h)
};

// SurfaceLayers::unseen bits of an empty cell. kEmptyColumn: its column holds no occupied
// voxel from the bottom of the map up to the clearance above its neighbours' surface
// and no ray passed through the voxel under that surface's level (nothing lower was seen,
// no ray went into a hole: not a drop; nothing above: not an obstacle). kNotErased: the
// voxel at that surface's level is not known free (no ray passed where the floor would
// be). Both: floor nobody saw (docs/unseen_floor.md).
constexpr uint8_t kEmptyColumn = 1;
constexpr uint8_t kNotErased = 2;

// SurfaceLayers::filled entries: why a cell empty in the map holds a surface in its layer.
// kFilledUnseen: no ray reached its floor-level voxel (unseen floor, enclosed by seen floor:
// floor by the rule). kFilledErased: a ray passed through that voxel (erased floor):
// floor for the plane fit and the segmentation only, so one floor stays one patch; no
// region and no seen surface holds it (docs/unseen_floor.md).
constexpr uint8_t kFilledUnseen = 1;
constexpr uint8_t kFilledErased = 2;

// Bit of neighbour (row + dr, col + dc), dr, dc in {-1, 0, 1} and not both 0, in a
// SurfaceLayers::solid_beside entry.
inline int NeighbourBit(int dr, int dc) {
  const int k = (dr + 1) * 3 + (dc + 1);
  return k < 4 ? k : k - 1;
}

struct SurfaceLayers {
  std::vector<HeightMap> layers;  // layer 0 holds the largest sheets; all share one grid
  // Per layer and cell, one bit per neighbour column (NeighbourBit): set when material
  // rises beside the cell's surface from its level - the neighbour column is occupied in
  // the voxel above the cell's top voxel and in the one above that or the top voxel's
  // own level (a wall, a riser, a higher step). There the surface does not end inside
  // its top voxel: it runs on to the material beside it, unless a gap narrower than a
  // voxel separates them, which no map of this resolution can show anyway. Where the
  // bit is clear (a drop, unknown space, the map's border) the true edge may lie
  // anywhere inside the top voxel.
  std::vector<std::vector<uint8_t>> solid_beside;
  // Per layer and cell, bits saying what is known of a cell empty in the layer
  // (kEmptyColumn, kNotErased); 0 for a cell with a surface. Empty when not computed.
  std::vector<std::vector<uint8_t>> unseen;
  // Per layer, the cells whose seen height FillSingleCellNoise moved by a voxel, at the
  // height the map saw (NaN elsewhere); empty when none moved. The repaired height is
  // what regions are fitted to; the seen one is where a robot may stand all the same
  // (a start foot on the voxel's top: geometry/seen_surface.h).
  std::vector<HeightMap> moved_as_seen;
  // Per layer and cell, kFilledUnseen or kFilledErased where the noise repair or the
  // enclosed-unseen fill gave an empty cell a surface, 0 elsewhere. Empty when not computed.
  std::vector<std::vector<uint8_t>> filled;
  int candidates = 0;             // surfaces that passed every test
  int no_room_above = 0;          // surfaces with an occupied voxel within the clearance
  int not_seen_from_above = 0;    // surfaces whose top voxel is not known free
  int isolated_voxels = 0;        // single voxels with no occupied neighbour, ignored
  int noise_cells_filled = 0;     // cells FillSingleCellNoise changed
  int enclosed_unseen_filled = 0; // unseen cells filled as enclosed floor
};

// Scan noise on a level surface, undone: a cell whose 8 neighbours all have one height
// and that is empty (a missed voxel) gets that height unless `unseen` (SurfaceLayers::
// unseen bits; nullptr: all allowed) says its column is not empty - a single erased
// voxel with floor seen all round and nothing below is floor (docs/unseen_floor.md); a cell exactly one voxel above or
// below a neighbourhood of which at least 7 of 8 agree is set to their height. Only holes
// with all 8 neighbours present are filled, so no surface grows past its edge. Returns the
// number of cells changed; `changed_cells` (optional) gets their indices appended.
int FillSingleCellNoise(HeightMap* height_map, const std::vector<uint8_t>* unseen = nullptr,
                        std::vector<int>* changed_cells = nullptr);

// Throws InputError as BuildHeightMap does (bad resolution or leaves, too many cells).
SurfaceLayers BuildSurfaceLayers(const OccupancyMap& map, const SurfaceLayerOptions& options);

}  // namespace mfp
