#include "terrain/extraction/internal/patch_safety.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "terrain/extraction/internal/surface_layers.h"

namespace mfp {

InsetsInCells InsetsToCells(const PatchDecompositionOptions& options, double res) {
  InsetsInCells insets;
  insets.base = options.inset_m / res;
  insets.drop = options.drop_inset_m / res;
  // A riser with no uncertainty is kept strictly off (by 0.1 um): a foot disk touching a
  // wall is not on free surface.
  insets.riser = (options.riser_inset_m > 0.0 ? options.riser_inset_m : 1e-7) / res;
  // An erased fill is kept strictly off as a riser with no uncertainty is.
  insets.erased = insets.base + 1e-7 / res;
  insets.max = insets.base + std::max(insets.drop, insets.riser);
  return insets;
}

std::vector<DiskOffset> DiskOffsets(double max_inset_cells, double res) {
  std::vector<DiskOffset> offsets;
  const int reach = static_cast<int>(std::ceil(max_inset_cells + 0.5));
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      const double ex = std::max(std::abs(dc) - 0.5, 0.0), ey = std::max(std::abs(dr) - 0.5, 0.0);
      const double d = std::sqrt(ex * ex + ey * ey);
      if (d < max_inset_cells - 1e-12 / res) offsets.push_back({dr, dc, d});
    }
  }
  return offsets;
}

bool ErasedFill(const PatchDecompositionOptions& options, int cell) {
  return options.filled != nullptr && (*options.filled)[static_cast<size_t>(cell)] == kFilledErased;
}

// The patch's cells over its bounding box, but its erased fills.
LocalGrid PatchMask(const HeightMap& hm, const PlanarPatch& patch, const PatchDecompositionOptions& options) {
  LocalGrid mask;
  int rmin = hm.rows, rmax = -1, cmin = hm.cols, cmax = -1;
  for (int cell : patch.cells) {
    rmin = std::min(rmin, cell / hm.cols);
    rmax = std::max(rmax, cell / hm.cols);
    cmin = std::min(cmin, cell % hm.cols);
    cmax = std::max(cmax, cell % hm.cols);
  }
  mask.row0 = rmin;
  mask.col0 = cmin;
  mask.rows = rmax - rmin + 1;
  mask.cols = cmax - cmin + 1;
  mask.cells.assign(static_cast<size_t>(mask.rows) * mask.cols, 0);
  for (int cell : patch.cells) mask.At(cell / hm.cols - rmin, cell % hm.cols - cmin) = !ErasedFill(options, cell);
  return mask;
}

// The edge uncertainty is added where the patch may end inside its boundary cell next to
// it - every neighbour unless material rises there (solid_beside). Each patch cell marks
// its outside neighbours (next to the patch; a drop unless its solid_beside bit says
// material rises there), so the work goes with the patch's cells, not its bounding box.
InsetField::InsetField(const HeightMap& hm, const LocalGrid& mask,
                       const PatchDecompositionOptions& options, const InsetsInCells& insets)
    : ring_(static_cast<int>(std::ceil(insets.max)) + 2),
      rows_(mask.rows),
      cols_(mask.cols),
      ext_cols_(mask.cols + 2 * ring_),
      max_(insets.max),
      grid_(static_cast<size_t>(mask.rows + 2 * ring_) * ext_cols_, insets.base) {
  constexpr uint8_t kNext = 1, kDrop = 2;
  std::vector<uint8_t> beside(grid_.size(), 0);
  auto ext = [&](int r, int c) { return static_cast<size_t>(r + ring_) * ext_cols_ + (c + ring_); };
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      if (!mask.At(r, c)) continue;
      const int p = hm.Index(mask.row0 + r, mask.col0 + c);
      const uint8_t solid = options.solid_beside == nullptr ? 0 : (*options.solid_beside)[static_cast<size_t>(p)];
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if ((dr == 0 && dc == 0) || mask.Contains(r + dr, c + dc)) continue;
          uint8_t& b = beside[ext(r + dr, c + dc)];
          b |= kNext;
          if (!(solid & (1u << NeighbourBit(dr, dc)))) b |= kDrop;
        }
      }
    }
  }
  for (int r = -ring_; r < mask.rows + ring_; ++r) {
    for (int c = -ring_; c < mask.cols + ring_; ++c) {
      const size_t i = ext(r, c);
      double& inset = grid_[i];
      if (mask.Contains(r, c)) {
        inset = -1.0;
        continue;
      }
      const int hr = mask.row0 + r, hc = mask.col0 + c;
      if (hm.Inside(hr, hc) && ErasedFill(options, hm.Index(hr, hc))) {
        inset = insets.erased;
        continue;
      }
      if (beside[i] & kNext) inset += (beside[i] & kDrop) ? insets.drop : insets.riser;
      // A cell asking no inset (point feet, no margin) still keeps regions off its
      // interior: the side and rotated-rectangle tests need a positive inset.
      inset = std::max(inset, 1e-6);
    }
  }
}

// Eroded mask: cells whose centre holds a whole foot disk. Only an outside cell (inset >= 0)
// takes the disk away, so a cell whose box of offsets lies in the patch keeps it without
// the offsets being tried (the patch's cells counted over boxes by summed rows and columns).
LocalGrid ErodedMask(const LocalGrid& mask, const InsetField& inset, const std::vector<DiskOffset>& offsets,
                     double res) {
  int reach = 0;
  for (const DiskOffset& o : offsets) reach = std::max({reach, std::abs(o.dr), std::abs(o.dc)});
  const int side = 2 * reach + 1;
  // held[(r + 1) * (cols + 1) + c + 1]: the patch's cells in rows [0, r] x columns [0, c].
  const size_t stride = static_cast<size_t>(mask.cols) + 1;
  std::vector<int> held(stride * (static_cast<size_t>(mask.rows) + 1), 0);
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      const size_t i = (static_cast<size_t>(r) + 1) * stride + static_cast<size_t>(c) + 1;
      held[i] = held[i - 1] + held[i - stride] - held[i - stride - 1] + (mask.At(r, c) ? 1 : 0);
    }
  }
  auto box_in_patch = [&](int r, int c) {
    if (r - reach < 0 || c - reach < 0 || r + reach >= mask.rows || c + reach >= mask.cols) return false;
    const size_t lo_r = static_cast<size_t>(r - reach), hi_r = static_cast<size_t>(r + reach) + 1;
    const size_t lo_c = static_cast<size_t>(c - reach), hi_c = static_cast<size_t>(c + reach) + 1;
    return held[hi_r * stride + hi_c] - held[lo_r * stride + hi_c] - held[hi_r * stride + lo_c] +
               held[lo_r * stride + lo_c] == side * side;
  };
  LocalGrid eroded = mask;
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      if (!mask.At(r, c) || box_in_patch(r, c)) continue;
      for (const DiskOffset& o : offsets) {
        const double cell_inset = inset.At(r + o.dr, c + o.dc);
        if (cell_inset >= 0.0 && res * o.dist_cells < res * cell_inset - 1e-12) {
          eroded.At(r, c) = 0;
          break;
        }
      }
    }
  }
  return eroded;
}

// Dual squares: spanned by the centres of cells (r, c) .. (r + 1, c + 1), all kept.
LocalGrid DualSquares(const LocalGrid& eroded) {
  LocalGrid dual;
  dual.rows = eroded.rows - 1;
  dual.cols = eroded.cols - 1;
  dual.cells.assign(static_cast<size_t>(dual.rows) * dual.cols, 0);
  for (int r = 0; r < dual.rows; ++r) {
    for (int c = 0; c < dual.cols; ++c) {
      dual.At(r, c) = eroded.At(r, c) && eroded.At(r + 1, c) && eroded.At(r, c + 1) &&
                      eroded.At(r + 1, c + 1);
    }
  }
  return dual;
}

}  // namespace mfp
