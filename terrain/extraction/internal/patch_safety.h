#pragma once
// The safety data of one planar patch's decomposition (patch_decomposition.h states the
// soundness argument): the patch's cells over their bounding box, each outside cell's
// inset, the cells whose centre holds a whole foot disk, and the complete dual squares
// they span. Private to the extraction library.
#include <cstdint>
#include <vector>

#include "terrain/extraction/height_map.h"
#include "terrain/extraction/internal/patch_decomposition.h"
#include "terrain/extraction/internal/plane_segmentation.h"

namespace mfp {

// A binary mask over a patch's bounding box.
struct LocalGrid {
  int row0 = 0, col0 = 0;  // height map cell of local (0, 0)
  int rows = 0, cols = 0;
  std::vector<uint8_t> cells;
  uint8_t& At(int r, int c) { return cells[static_cast<size_t>(r) * cols + c]; }
  uint8_t At(int r, int c) const { return cells[static_cast<size_t>(r) * cols + c]; }
  bool Contains(int r, int c) const { return r >= 0 && r < rows && c >= 0 && c < cols && At(r, c); }
};

// The insets of one decomposition, in cells.
struct InsetsInCells {
  double base = 0.0;   // from every cell outside the patch
  double drop = 0.0;   // in addition, next to the patch where its surface may end
  double riser = 0.0;  // in addition, next to the patch where material rises
  double erased = 0.0; // the whole inset from an erased fill (PatchDecompositionOptions::filled)
  double max = 0.0;    // the largest of them all
};

InsetsInCells InsetsToCells(const PatchDecompositionOptions& options, double res);

// Offset of a cell whose square comes closer than the largest inset to a cell centre,
// with that distance [cells].
struct DiskOffset {
  int dr, dc;
  double dist_cells;
};

std::vector<DiskOffset> DiskOffsets(double max_inset_cells, double res);

// The patch's cells over its bounding box, but its erased fills (options.filled).
LocalGrid PatchMask(const HeightMap& hm, const PlanarPatch& patch, const PatchDecompositionOptions& options);

// Whether options.filled marks the height map cell an erased fill.
bool ErasedFill(const PatchDecompositionOptions& options, int cell);

// Each outside cell's inset [cells] over the mask's bounding box plus a ring (-1: a patch
// cell); beyond the ring, the largest inset.
class InsetField {
 public:
  InsetField(const HeightMap& hm, const LocalGrid& mask, const PatchDecompositionOptions& options,
             const InsetsInCells& insets);
  double At(int r, int c) const {
    if (r < -ring_ || r >= rows_ + ring_ || c < -ring_ || c >= cols_ + ring_) return max_;
    return grid_[static_cast<size_t>(r + ring_) * ext_cols_ + (c + ring_)];
  }
  int ring() const { return ring_; }

 private:
  int ring_, rows_, cols_, ext_cols_;
  double max_;
  std::vector<double> grid_;
};

// Eroded mask: cells whose centre holds a whole foot disk.
LocalGrid ErodedMask(const LocalGrid& mask, const InsetField& inset, const std::vector<DiskOffset>& offsets,
                     double res);

// Dual squares: spanned by the centres of cells (r, c) .. (r + 1, c + 1), all kept.
LocalGrid DualSquares(const LocalGrid& eroded);

}  // namespace mfp
