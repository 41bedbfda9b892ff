#pragma once
// Height-map files: a .npy array of heights and a small YAML that says where it lies.
//
//   heights: stairs.npy     # the array, relative to the YAML (optional when the YAML
//                           # sits beside the array as NAME.yaml for NAME.npy)
//   resolution: 0.02        # cell edge [m]
//   origin: [-1.0, -2.0]    # x, y of the centre of cell (0, 0) [m]
//   unknown: nan            # value of unknown cells besides NaN (optional; default nan)
//   variance: stairs_var.npy  # optional per-cell height variance [m^2], same shape
//   max_variance: 0.0001    # cells with a larger variance are unknown [m^2]
//                           # (optional; default (resolution / 2)^2)
//   frame: world            # optional, for the record
//
// heights[i, j] is the cell centred at x = origin_x + i * resolution, y = origin_y +
// j * resolution (numpy's first index along x).
#include <cstddef>
#include <string>

#include "io/internal/npy_array.h"
#include "terrain/extraction/height_grid.h"

namespace mfp {

// True for the names a height map comes in: .npy, .yaml, .yml.
bool IsHeightMapPath(const std::string& path);

// Loads NAME.npy with NAME.yaml beside it, or a YAML naming its array. Throws InputError
// naming the file and field (missing file or key, out-of-range value, arrays of different
// shapes, more than max_cells cells) and whatever ValidateHeightGrid rejects.
HeightGrid LoadHeightGridFile(const std::string& path, size_t max_cells = kDefaultMaxHeightMapCells);

// A grid from an array (heights[i, j] = array row i, column j): cells equal to
// unknown_value (when finite) become NaN. Validates the result.
HeightGrid HeightGridFromArray(const NpyArray& heights, double resolution_m, double origin_x_m,
                               double origin_y_m, double unknown_value,
                               size_t max_cells = kDefaultMaxHeightMapCells);

}  // namespace mfp
