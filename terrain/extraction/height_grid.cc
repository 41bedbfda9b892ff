#include "terrain/extraction/height_grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "base/check.h"

namespace mfp {
namespace {

std::string CellName(const HeightGrid& grid, size_t index) {
  const size_t ny = static_cast<size_t>(grid.ny);
  return "(" + std::to_string(index / ny) + ", " + std::to_string(index % ny) + ")";
}

bool Known(const HeightGrid& grid, size_t index) {
  const float h = grid.heights_m[index];
  if (std::isnan(h)) return false;
  if (grid.variances_m2.empty()) return true;
  const float v = grid.variances_m2[index];
  return !std::isnan(v) && v <= grid.max_variance_m2;
}

}  // namespace

void ValidateHeightGrid(const HeightGrid& grid, size_t max_cells) {
  if (!std::isfinite(grid.resolution_m) || grid.resolution_m <= 0.0 || grid.resolution_m > 10.0) {
    std::ostringstream msg;
    msg << "height map resolution " << grid.resolution_m << " m is outside the allowed range (0, 10] m";
    throw InputError(msg.str());
  }
  if (!grid.origin_m.allFinite()) throw InputError("height map origin must be two finite numbers [m]");
  if (grid.nx <= 0 || grid.ny <= 0) {
    throw InputError("height map has " + std::to_string(grid.nx) + " x " + std::to_string(grid.ny) +
                     " cells: it needs at least one cell");
  }
  const size_t cells = static_cast<size_t>(grid.nx) * static_cast<size_t>(grid.ny);
  if (cells > max_cells) {
    throw InputError("height map has " + std::to_string(grid.nx) + " x " + std::to_string(grid.ny) +
                     " cells, more than the limit of " + std::to_string(max_cells) +
                     ": give a smaller or coarser map");
  }
  if (grid.heights_m.size() != cells) {
    throw InputError("height map heights hold " + std::to_string(grid.heights_m.size()) +
                     " values for " + std::to_string(cells) + " cells");
  }
  if (!grid.variances_m2.empty() && grid.variances_m2.size() != cells) {
    throw InputError("height map variances hold " + std::to_string(grid.variances_m2.size()) +
                     " values for " + std::to_string(cells) + " cells (give one per cell, or none)");
  }
  if (!(grid.max_variance_m2 >= 0.0)) throw InputError("height map max_variance must be >= 0 m^2");
  for (size_t k = 0; k < cells; ++k) {
    const float h = grid.heights_m[k];
    if (!std::isnan(h) && !(std::abs(h) <= kMaxHeightGridHeightM)) {
      std::ostringstream msg;
      msg << "height map cell " << CellName(grid, k) << " has height " << h
          << " m, outside [-" << kMaxHeightGridHeightM << ", " << kMaxHeightGridHeightM
          << "] m (unknown cells are NaN or the map's unknown value)";
      throw InputError(msg.str());
    }
    if (!grid.variances_m2.empty()) {
      const float v = grid.variances_m2[k];
      if (!std::isnan(v) && !(v >= 0.0f && std::isfinite(v))) {
        std::ostringstream msg;
        msg << "height map cell " << CellName(grid, k) << " has variance " << v
            << " m^2: variances must be finite and >= 0 (NaN = unknown)";
        throw InputError(msg.str());
      }
    }
  }
}

SurfaceLayers HeightGridLayers(const HeightGrid& grid, double riser_min_m, size_t max_cells) {
  ValidateHeightGrid(grid, max_cells);
  MFP_CHECK(riser_min_m >= 0.0);
  // The pipeline's grid: rows along y, columns along x, origin at the lower corner.
  HeightMap layer;
  layer.resolution_m = grid.resolution_m;
  layer.origin_world_m = grid.origin_m - Eigen::Vector2d::Constant(0.5 * grid.resolution_m);
  layer.rows = grid.ny;
  layer.cols = grid.nx;
  layer.height_m.assign(grid.heights_m.size(), std::numeric_limits<float>::quiet_NaN());
  SurfaceLayers out;
  for (int i = 0; i < grid.nx; ++i) {
    for (int j = 0; j < grid.ny; ++j) {
      const size_t k = grid.Index(i, j);
      if (!Known(grid, k)) continue;
      layer.height_m[static_cast<size_t>(layer.Index(j, i))] = grid.heights_m[k];
      ++out.candidates;
    }
  }
  std::vector<uint8_t> bits(layer.height_m.size(), 0);
  for (int r = 0; r < layer.rows; ++r) {
    for (int c = 0; c < layer.cols; ++c) {
      const float h = layer.height_m[static_cast<size_t>(layer.Index(r, c))];
      if (std::isnan(h)) continue;
      uint8_t b = 0;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if ((dr == 0 && dc == 0) || !layer.Inside(r + dr, c + dc)) continue;
          // A height map's columns are solid below their surface: a known neighbour a
          // riser higher is material rising beside this cell. NaN compares false.
          if (layer.height_m[static_cast<size_t>(layer.Index(r + dr, c + dc))] >= h + riser_min_m) {
            b = static_cast<uint8_t>(b | (1u << NeighbourBit(dr, dc)));
          }
        }
      }
      bits[static_cast<size_t>(layer.Index(r, c))] = b;
    }
  }
  out.layers.push_back(std::move(layer));
  out.solid_beside.push_back(std::move(bits));
  return out;
}

RegionExtractionResult ExtractRegionsFromHeightGrid(const HeightGrid& grid,
                                                    const RegionExtractorOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // A riser that leaves the patch's plane tolerance is material beside it, as one voxel
  // of wall is in a voxel map.
  const double riser_min_m = std::max(0.0, options.grow_tolerance_voxels * grid.resolution_m);
  SurfaceLayers layers = HeightGridLayers(grid, riser_min_m, options.max_height_map_cells);
  const double layers_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RegionExtractionResult result = ExtractRegionsFromLayers(std::move(layers), options);
  result.stats.height_map_s = layers_s;
  result.stats.total_s += layers_s;
  return result;
}

}  // namespace mfp
