#include "terrain/quality/height_grid_sampling.h"

#include <cmath>
#include <limits>

#include "base/check.h"
#include "terrain/quality/terrain_quality.h"

namespace mfp {

HeightGrid SampleHeightGrid(const TerrainDescription& terrain, double resolution_m) {
  if (terrain.boxes.empty()) throw InputError("a height map of a terrain needs at least one box");
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    throw InputError("height map resolution must be > 0 m");
  }
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const TerrainBox& box : terrain.boxes) {
    for (const Eigen::Vector3d& corner : BoxCorners(box)) {
      lo = lo.cwiseMin(corner.head<2>());
      hi = hi.cwiseMax(corner.head<2>());
    }
  }
  HeightGrid grid;
  grid.resolution_m = resolution_m;
  const double i0 = std::floor(lo.x() / resolution_m), j0 = std::floor(lo.y() / resolution_m);
  const double nx = std::ceil(hi.x() / resolution_m) - i0 + 1, ny = std::ceil(hi.y() / resolution_m) - j0 + 1;
  if (nx * ny > static_cast<double>(kDefaultMaxHeightMapCells)) {
    throw InputError("the terrain's height map at " + std::to_string(resolution_m) + " m would have too many cells");
  }
  grid.origin_m = Eigen::Vector2d(i0 * resolution_m, j0 * resolution_m);
  grid.nx = static_cast<int>(nx);
  grid.ny = static_cast<int>(ny);
  grid.heights_m.resize(static_cast<size_t>(grid.nx) * static_cast<size_t>(grid.ny));
  const double offsets[3] = {-0.45 * resolution_m, 0.0, 0.45 * resolution_m};
  for (int i = 0; i < grid.nx; ++i) {
    for (int j = 0; j < grid.ny; ++j) {
      const double x = grid.origin_m.x() + i * resolution_m, y = grid.origin_m.y() + j * resolution_m;
      double highest = std::numeric_limits<double>::quiet_NaN();
      for (double dx : offsets) {
        for (double dy : offsets) {
          const double h = TrueTopHeight(terrain, x + dx, y + dy);
          if (!std::isnan(h) && !(h <= highest)) highest = h;
        }
      }
      grid.heights_m[grid.Index(i, j)] = static_cast<float>(highest);
    }
  }
  return grid;
}

}  // namespace mfp
