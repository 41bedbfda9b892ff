#pragma once
// Height maps of box descriptions, sampled exactly: what an ideal elevation mapper would
// report for a terrain of boxes. Tests, mfp-make-log and mfp-terrain-bench make height
// maps with known true surfaces from it.
#include "geometry/terrain_description.h"
#include "terrain/extraction/height_grid.h"

namespace mfp {

// Per cell, the highest box surface (TrueTopHeight) over a 3 x 3 pattern of points inside
// the cell (its centre and +-0.45 cells): an elevation mapper's "highest point seen in the
// cell", so a surface reaching into a cell raises it and a riser never reaches into a
// lower cell by more than 0.05 cells. Over the boxes' x-y extent, on a grid of the given
// resolution whose cell centres lie on multiples of it; NaN (unknown) where no box is. Throws InputError when the terrain has no boxes or the
// grid would exceed kDefaultMaxHeightMapCells.
HeightGrid SampleHeightGrid(const TerrainDescription& terrain, double resolution_m);

}  // namespace mfp
