#pragma once
// Segments a height map into planar patches by region growing: a patch starts at a smooth
// cell and takes in 4-connected neighbours whose height lies within a tolerance of the
// patch's current least-squares plane (refitted as it grows), so a voxelised tilt (a
// staircase of one-voxel risers) becomes one tilted patch while a step of two voxels or
// more ends it. Cells further than max_residual_m from the final plane are dropped, and
// the plane is fitted again to the cells kept, so a neighbour's cells that joined the
// growth do not lift it. Sensor noise stays in the patch: a small group of cells one
// voxel off the plane (a pit or a bump), or of unseen cells, enclosed on all sides by
// the patch's own cells, is part of the surface; a longer run (a riser) or a group at the
// patch's border (an edge) is not. With noise_patch_foot_radius_m, a noisier surface is
// grown on noise-free levels (noise_levels.h: small groups of cells one voxel off their
// neighbourhood's median count at that median) and its patches too small to hold a foot
// join the surface around them (noise_patches.h); the planes stay fitted to the cells'
// own heights.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "terrain/extraction/height_map.h"
#include "terrain/extraction/internal/noise_levels.h"

namespace mfp {

struct SegmentationOptions {
  double grow_tolerance_m = 0.0;    // join a patch when |h - plane| <= this [m]
  double max_residual_m = 0.0;      // drop cells further than this from the final plane [m]
  double max_seed_roughness_m = 0.0;  // only cells at least this smooth start a patch [m]
  // Noise kept in a patch: a 4-connected group of at most noise_max_cells cells, each
  // within noise_tolerance_m of the plane or empty and marked in `unseen`, whose every
  // neighbour (8-connected) outside the group is a patch cell (0 cells: none kept).
  double noise_tolerance_m = 0.0;
  int noise_max_cells = 0;
  // Per height map cell, kEmptyColumn | kNotErased where an empty cell may be floor nobody saw (nothing occupied
  // in its column, not known free: SurfaceLayers::unseen bits); nullptr: no empty cell is.
  const std::vector<uint8_t>* unseen = nullptr;
  // A patch none of whose cells holds a disk of this radius on the patch's own cells
  // (the foot, its margin and the edge uncertainty) holds no foot: it is noise of the
  // surface around it when within noise_tolerance_m of that surface (noise_patches.h);
  // 0: patches stay as grown [m].
  double noise_patch_foot_radius_m = 0.0;
  // The height map's NoiseFreeLevels (noise_tolerance_m, noise_max_cells) when computed
  // already; nullptr: computed here when needed.
  const NoiseLevels* noise_levels = nullptr;
};

struct PlanarPatch {
  std::vector<int> cells;  // height map cell indices
  // The plane z = a x + b y + c (world, metres) fitted to the cells.
  double a = 0.0, b = 0.0, c = 0.0;
  double max_residual_m = 0.0;  // of the cells within the final plane's fit (noise not counted)
  int noise_cells = 0;          // cells kept as noise (off the plane or unseen)
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();
  double SlopeRad() const;
  double HeightAt(const Eigen::Vector2d& xy_world_m) const { return a * xy_world_m.x() + b * xy_world_m.y() + c; }
};

std::vector<PlanarPatch> SegmentPlanarPatches(const HeightMap& height_map,
                                              const SurfaceAnalysis& surface,
                                              const SegmentationOptions& options);

}  // namespace mfp
