#pragma once
// The covers of a patch's complete dual squares (patch_safety.h): on the
// height map's grid, or on a grid rotated into the patch's principal frame (each keeps
// the inset of every outside cell exactly), or by convex pieces of the dual squares. Private to the extraction library.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "terrain/extraction/internal/patch_decomposition.h"
#include "terrain/extraction/internal/patch_safety.h"

namespace mfp {

// What the two covers share: the patch's local frame ("centre units": x = column offset
// from the centre of local cell (0, 0)) and its safety data.
struct CoverInput {
  const LocalGrid* mask;
  const LocalGrid* dual;
  const InsetField* inset;
  double max_inset_cells;
  double res;
  Eigen::Vector2d origin_center;
  Eigen::Vector2d ToWorld(const Eigen::Vector2d& local) const { return origin_center + res * local; }
};

inline int MinRectCells(double min_area_xy_m2, double cell_area_m2) {
  return std::max(1, static_cast<int>(std::ceil(min_area_xy_m2 / cell_area_m2 - 1e-9)));
}

// Rectangles of complete dual squares end on cell centres; each side then moves out as
// far as its strip keeps the inset from every cell outside the patch, so regions lose
// less than the cell quantisation of the inset.
std::vector<Quad2d> CoverOnGrid(const CoverInput& in, const PatchDecompositionOptions& options);

// The cover on a grid rotated by angle [rad] into the patch's principal frame.
std::vector<Quad2d> CoverRotated(const CoverInput& in, double angle, const PatchDecompositionOptions& options);

// Convex pieces of the complete dual squares (ConvexCoverOfSquares), in world x-y.
std::vector<Polygon2d> CoverConvex(const CoverInput& in, const PatchDecompositionOptions& options);

}  // namespace mfp
