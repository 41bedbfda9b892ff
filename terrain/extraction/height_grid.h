#pragma once
// Height maps as elevation mappers produce them (grid_map, elevation_mapping, a numpy
// array): a 2-D grid of surface heights, in the terrain pipeline. The grid becomes one
// surface layer (surface_layers.h) and runs through the same stages as a voxel map's
// layers (region_extractor.h), with the same soundness: an unknown cell is not floor and
// the drop beside a cell is inset like a drop in a voxel map. A height map says nothing
// about overhangs, so it has one layer and no clearance test. Plain Eigen.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "terrain/extraction/height_map.h"
#include "terrain/extraction/internal/surface_layers.h"
#include "terrain/extraction/region_extractor.h"

namespace mfp {

struct HeightGrid {
  double resolution_m = 0.0;                          // cell edge [m]
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // centre of cell (0, 0) [m, world]
  int nx = 0;  // cells along x (first index)
  int ny = 0;  // cells along y (second index)
  // heights_m[i * ny + j]: the surface height of the cell centred at
  // origin + (i, j) * resolution [m]; NaN = unknown.
  std::vector<float> heights_m;
  // Empty, or per cell like heights_m: the variance of the height [m^2]; NaN = unknown.
  std::vector<float> variances_m2;
  // Cells whose variance exceeds this are unknown [m^2] (only with variances).
  double max_variance_m2 = 0.0;

  size_t Index(int i, int j) const { return static_cast<size_t>(i) * static_cast<size_t>(ny) + static_cast<size_t>(j); }
};

// Largest height magnitude accepted [m]: anything larger is a unit or encoding error.
constexpr double kMaxHeightGridHeightM = 1e4;

// Throws InputError naming the field when the resolution is not positive and finite (at
// most 10 m), the origin is not finite, the grid is empty or has more than max_cells cells,
// the arrays do not match nx * ny, a height is infinite or larger than
// kMaxHeightGridHeightM, or a variance is negative or infinite.
void ValidateHeightGrid(const HeightGrid& grid, size_t max_cells = kDefaultMaxHeightMapCells);

// The grid as one surface layer: known cells (finite height, variance within the limit)
// are surfaces; a neighbour at least riser_min_m higher is solid beside the cell (the
// surface runs on to it), a lower, unknown or missing neighbour is a drop. Validates first.
SurfaceLayers HeightGridLayers(const HeightGrid& grid, double riser_min_m,
                               size_t max_cells = kDefaultMaxHeightMapCells);

// The regions of a height map: HeightGridLayers with a riser of one tolerance
// (grow_tolerance_voxels cells), then ExtractRegionsFromLayers. Throws InputError as
// ValidateHeightGrid and ExtractRegions do. Resolution plays the voxel's part in every
// tolerance given in voxels.
RegionExtractionResult ExtractRegionsFromHeightGrid(const HeightGrid& grid,
                                                    const RegionExtractorOptions& options);

}  // namespace mfp
