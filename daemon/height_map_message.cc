#include "daemon/height_map_message.h"

#include <cstdint>
#include <sstream>

#include "base/check.h"
#include "lcmtypes/message_guard.h"

namespace mfp {

HeightGrid HeightGridFromMessage(const height_map_t& message, const std::string& what) {
  HeightGrid grid;
  grid.resolution_m = message.resolution;
  grid.origin_m = Eigen::Vector2d(message.origin_x, message.origin_y);
  grid.nx = message.nx;
  grid.ny = message.ny;
  if (message.nx <= 0 || message.ny <= 0) {
    throw InputError(what + ": nx = " + std::to_string(message.nx) + ", ny = " + std::to_string(message.ny) +
                     ": a height map needs at least one cell");
  }
  const size_t cells = static_cast<size_t>(message.nx) * static_cast<size_t>(message.ny);
  if (cells > kDefaultMaxHeightMapCells) {
    throw InputError(what + ": " + std::to_string(message.nx) + " x " + std::to_string(message.ny) +
                     " cells, more than the limit of " + std::to_string(kDefaultMaxHeightMapCells));
  }
  grid.heights_m.reserve(cells);
  for (const std::vector<float>& row : message.heights) {
    if (row.size() != static_cast<size_t>(message.ny)) {
      throw InputError(what + ": a row of heights holds " + std::to_string(row.size()) + " values, not ny = " +
                       std::to_string(message.ny));
    }
    grid.heights_m.insert(grid.heights_m.end(), row.begin(), row.end());
  }
  if (message.num_variances != 0) {
    if (static_cast<size_t>(message.num_variances) != cells) {
      throw InputError(what + ": num_variances = " + std::to_string(message.num_variances) +
                       "; give 0 or nx * ny = " + std::to_string(cells));
    }
    grid.variances_m2 = message.variances;
    grid.max_variance_m2 = message.max_variance > 0.0 ? message.max_variance
                                                      : 0.25 * message.resolution * message.resolution;
  }
  try {
    ValidateHeightGrid(grid);
  } catch (const InputError& e) {
    throw InputError(what + ": " + e.what());
  }
  return grid;
}

height_map_t HeightMapMessage(const HeightGrid& grid, int64_t utime, const std::string& frame) {
  height_map_t m{};
  m.utime = utime;
  m.frame = frame;
  m.resolution = grid.resolution_m;
  m.origin_x = grid.origin_m.x();
  m.origin_y = grid.origin_m.y();
  m.nx = grid.nx;
  m.ny = grid.ny;
  for (int i = 0; i < grid.nx; ++i) {
    const auto row = grid.heights_m.begin() + static_cast<std::ptrdiff_t>(grid.Index(i, 0));
    m.heights.emplace_back(row, row + grid.ny);
  }
  m.num_variances = static_cast<int32_t>(grid.variances_m2.size());
  m.variances = grid.variances_m2;
  m.max_variance = grid.variances_m2.empty() ? 0.0 : grid.max_variance_m2;
  return m;
}

HeightGrid HeightGridFromBytes(const std::string& bytes, size_t max_bytes, const std::string& what) {
  height_map_t message;
  const std::string error = DecodeGuarded(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(),
                                          max_bytes, &message);
  if (!error.empty()) throw InputError(what + ": " + error);
  return HeightGridFromMessage(message, what);
}

}  // namespace mfp
