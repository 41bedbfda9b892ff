#pragma once
// Segments a height map into planar patches by region growing: a patch starts at a smooth
// cell and takes in 4-connected neighbours whose height lies within a tolerance of the
// patch's current least-squares plane (refitted as it grows), so a voxelised tilt (a
// staircase of one-voxel risers) becomes one tilted patch while a step of two voxels or
// more ends it. Cells further than max_residual_m from the final plane are dropped.
#include <Eigen/Core>
#include <vector>

#include "terrain/extraction/height_map.h"

namespace mfp {

struct SegmentationOptions {
  double grow_tolerance_m = 0.0;    // join a patch when |h - plane| <= this [m]
  double max_residual_m = 0.0;      // drop cells further than this from the final plane [m]
  double max_seed_roughness_m = 0.0;  // only cells at least this smooth start a patch [m]
};

struct PlanarPatch {
  std::vector<int> cells;  // height map cell indices
  // The plane z = a x + b y + c (world, metres) fitted to the cells.
  double a = 0.0, b = 0.0, c = 0.0;
  double max_residual_m = 0.0;
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();
  double SlopeRad() const;
  double HeightAt(const Eigen::Vector2d& xy_world_m) const { return a * xy_world_m.x() + b * xy_world_m.y() + c; }
};

std::vector<PlanarPatch> SegmentPlanarPatches(const HeightMap& height_map,
                                              const SurfaceAnalysis& surface,
                                              const SegmentationOptions& options);

}  // namespace mfp
