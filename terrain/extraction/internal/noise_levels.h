#pragma once
// The levels a noisy surface is segmented on (issue 25). A real floor's top voxel jumps
// by a voxel about the surface, so region growing from a seed at one level stops two
// voxels away and the local fits are too rough to seed. A cell one voxel off the median
// of its 3 x 3 neighbourhood, in an 8-connected group of at most max_cells such cells on
// the same side that stands alone (every seen cell around it beyond it on the other
// side: a bump, a pit), is noise: its level is that median. A larger group, a group with
// cells of its level beside it (a riser is a run of cells; a voxelised tilt's staircase),
// or a cell further off (a drop) keeps its height.
#include <cstdint>
#include <vector>

#include "terrain/extraction/height_map.h"

namespace mfp {

struct NoiseLevels {
  // Both empty when denoised_cells is 0 (the levels are the heights then).
  HeightMap levels;               // the height map with noise cells at their neighbourhood's level
  std::vector<uint8_t> denoised;  // per cell, 1 where the level differs from the height
  int denoised_cells = 0;
};

// tolerance_m: how far off its neighbourhood a noise cell may lie (at least half a voxel
// off counts as off). surface_cells: the map's cells with a height (SurfaceAnalysis::cells),
// ascending.
NoiseLevels NoiseFreeLevels(const HeightMap& height_map, const std::vector<int>& surface_cells, double tolerance_m,
                            int max_cells);

// A surface cell one voxel (up to the tolerance) above (side +1) or below (-1) its
// neighbourhood's median.
struct OffCell {
  int cell;
  int8_t side;
  float median;  // [m]
};

// NoiseFreeLevels in two steps: the off cells of every layer, found in bands of rows on
// `threads` threads (each cell judged on its own neighbourhood), ascending per layer; then
// the levels of one height map from its off cells.
// surfaces: per layer its SurfaceCellsOf (the cells judged).
std::vector<std::vector<OffCell>> OffCellsOfLayers(const std::vector<HeightMap>& layers,
                                                   const std::vector<SurfaceAnalysis>& surfaces, double tolerance_m,
                                                   int threads);
NoiseLevels NoiseFreeLevelsFrom(const HeightMap& height_map, const std::vector<OffCell>& off, int max_cells);

// Whether the cell and its 8 neighbours are all seen at one level (within half a voxel):
// a seed for a patch on a surface too noisy for the local fit's roughness.
bool FlatLevel(const HeightMap& levels, int cell);

}  // namespace mfp
