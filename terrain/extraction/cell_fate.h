#pragma once
// Why a surface cell of a layer is or is not covered by a region: what the extractor
// did with each cell, recorded on request (RegionExtractorOptions::record_cell_fates) so
// a bench can split the floor it misses into causes. Diagnostic only; the regions do not
// depend on it.
#include <cstdint>

namespace mfp {

enum class CellFate : uint8_t {
  kNoSurface = 0,    // empty in this layer
  kNotInPatch,       // a surface the segmentation left out of every patch (no seed, off the plane)
  kSteepPatch,       // in a patch steeper than max_slope_rad
  kSmallPatch,       // in a patch smaller than a foot, or one the inset left no region of
  kNotDecomposed,    // in a patch left when the deadline or max_regions ended the work
  kInsetOffPatch,    // inset: a cell within the certification radius (centre to centre:
                     // foot + margin + edge uncertainty) is not in the patch
  kInsetBeyond,      // inset: only by cells beyond that radius (the inset is measured from
                     // the outside cell's square, not its centre)
  kUncovered,        // keeps a foot disk, but no region covers its centre (the cover stopped)
  kCovered,          // inside a region
};
constexpr int kCellFateCount = 9;

// A short name per fate, for tables.
inline const char* CellFateName(CellFate fate) {
  switch (fate) {
    case CellFate::kNoSurface: return "no_surface";
    case CellFate::kNotInPatch: return "not_in_patch";
    case CellFate::kSteepPatch: return "steep_patch";
    case CellFate::kSmallPatch: return "small_patch";
    case CellFate::kNotDecomposed: return "not_decomposed";
    case CellFate::kInsetOffPatch: return "inset_off_patch";
    case CellFate::kInsetBeyond: return "inset_beyond";
    case CellFate::kUncovered: return "uncovered";
    case CellFate::kCovered: return "covered";
  }
  return "?";
}

}  // namespace mfp
