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
#include <limits>
#include <vector>

#include "terrain/height_map.h"
#include "terrain/occupancy_map.h"

namespace mfp {

struct SurfaceLayerOptions {
  // Free space a surface needs above it [m]; the planner passes the robot's stance
  // height plus a margin. Infinity: only the highest surface of each column.
  double clearance_m = std::numeric_limits<double>::infinity();
  double step_gate_m = 0.0;           // neighbouring surfaces closer than this join a sheet [m]
  bool require_seen_from_above = true;  // applies only when the map stores free space
  bool drop_isolated_voxels = true;
  bool fill_single_cell_noise = true;   // FillSingleCellNoise on every layer
  size_t max_cells = kDefaultMaxHeightMapCells;
};

struct SurfaceLayers {
  std::vector<HeightMap> layers;  // layer 0 holds the largest sheets; all share one grid
  int candidates = 0;             // surfaces that passed every test
  int no_room_above = 0;          // surfaces with an occupied voxel within the clearance
  int not_seen_from_above = 0;    // surfaces whose top voxel is not known free
  int isolated_voxels = 0;        // single voxels with no occupied neighbour, ignored
  int noise_cells_filled = 0;     // cells FillSingleCellNoise changed
};

// Scan noise on a level surface, undone: a cell whose 8 neighbours all have one height
// and that is empty (a missed voxel) gets that height; a cell exactly one voxel above or
// below a neighbourhood of which at least 7 of 8 agree is set to their height. Only holes
// with all 8 neighbours present are filled, so no surface grows past its edge. Returns the
// number of cells changed.
int FillSingleCellNoise(HeightMap* height_map);

// Throws InputError as BuildHeightMap does (bad resolution or leaves, too many cells).
SurfaceLayers BuildSurfaceLayers(const OccupancyMap& map, const SurfaceLayerOptions& options);

}  // namespace mfp
