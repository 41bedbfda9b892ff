#pragma once
// height_map_t (channel MFP_HEIGHT_MAP) to the terrain pipeline's HeightGrid.
#include <string>

#include "mfp/height_map_t.hpp"
#include "terrain/extraction/height_grid.h"

namespace mfp {

// The map_function format of a height_map_t: the bytes are the encoded message.
inline constexpr const char* kHeightMapFormat = "height_map_t";

// Throws InputError naming `what` and the field when a row of heights does not hold ny
// values, num_variances is neither 0 nor nx * ny, or ValidateHeightGrid rejects the grid.
HeightGrid HeightGridFromMessage(const height_map_t& message, const std::string& what);

// The message of a grid (heights and variances in the grid's order).
height_map_t HeightMapMessage(const HeightGrid& grid, int64_t utime, const std::string& frame);

// Decodes (guarded, at most max_bytes) and converts; throws InputError on a message that
// does not decode.
HeightGrid HeightGridFromBytes(const std::string& bytes, size_t max_bytes, const std::string& what);

}  // namespace mfp
