#pragma once
// Joins the small patches a noisy floor splits into (issue 25). A real floor's top voxel
// scatters by a voxel about the surface, and region growing from a seed at one level
// stops at cells two voxels from it, so a floor becomes interleaved patches at its
// levels, each too small to hold a foot. A patch too small to hold a foot is noise of
// the surface around it; a patch that can hold one is a surface of its own (a stone one
// voxel above its neighbour stays a step).
//
// Patches are joined across 4-adjacent cells at most two voxels apart in height, only
// where at least one side is small (no cell of it holds a disk of noise_patch_foot_radius_m
// on its own cells), and never two large patches
// into one group. A group with a large patch keeps that patch's plane: a small patch
// joins it only when each of its cells lies within noise_tolerance_m of that plane (the
// region's height is the surface's height, not lifted by its noise). A group of small
// patches only is fitted one plane, and is one patch when every cell lies within
// noise_tolerance_m of it. The joined patch's cells outside its plane's max_residual_m
// count as noise (PlanarPatch::noise_cells).
#include <vector>

#include "terrain/extraction/height_map.h"
#include "terrain/extraction/internal/plane_segmentation.h"

namespace mfp {

// Fits the plane z = a x + b y + c (world) of `plane` to the cells seen in the height
// map (NaN cells are left out); false, and `plane` unchanged, when they do not fix one.
bool FitPlaneToSeenCells(const HeightMap& height_map, const std::vector<int>& cells, PlanarPatch* plane);

// Replaces `patches` by the joined ones (order: as the first member of each group);
// nothing changes when options.noise_patch_foot_radius_m is 0. surface_cells: the height
// map's cells with a height (SurfaceAnalysis::cells), ascending.
void JoinNoisePatches(const HeightMap& height_map, const std::vector<int>& surface_cells,
                      const SegmentationOptions& options, std::vector<PlanarPatch>* patches);

}  // namespace mfp
