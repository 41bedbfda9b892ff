#pragma once
// mfp-terrain-bench's height-map rows: terrains of the catalogue sampled as height maps
// (height_grid_sampling.h), extracted through the height-map entry point, timed and
// judged against the true boxes like the voxel maps.
#include "terrain/extraction/region_extractor.h"

namespace mfp {

// Prints one row per height map (same columns as the voxel maps). Returns true when every
// map's soundness is at least 0.99.
bool PrintHeightMapRows(const RegionExtractorOptions& options, int runs);

}  // namespace mfp
