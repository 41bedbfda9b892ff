#include "terrain/extraction/internal/patch_safety.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "terrain/extraction/height_map.h"

namespace mfp {
namespace {

// Every offset of the disk tried for every patch cell: the definition ErodedMask keeps.
LocalGrid ErodedByEveryOffset(const LocalGrid& mask, const InsetField& inset, const std::vector<DiskOffset>& offsets,
                              double res) {
  LocalGrid eroded = mask;
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      if (!mask.At(r, c)) continue;
      for (const DiskOffset& o : offsets) {
        const double cell_inset = inset.At(r + o.dr, c + o.dc);
        if (cell_inset >= 0.0 && res * o.dist_cells < res * cell_inset - 1e-12) eroded.At(r, c) = 0;
      }
    }
  }
  return eroded;
}

// Patches of wide floor with holes, thin arms and a ragged edge, eroded at insets from a
// fraction of a cell to several cells: the cells whose box of offsets lies in the patch
// are passed over without the offsets, and every cell keeps or loses its disk as when
// every offset is tried. It fails when a cell next to a hole, an edge or the mask's
// bounds is taken for one inside the patch.
TEST(PatchSafetyTest, ErodedMaskIsEveryOffsetsErosion) {
  std::mt19937 rng(11);
  const double res = 0.02;
  HeightMap hm;
  hm.resolution_m = res;
  hm.rows = 90;
  hm.cols = 110;
  hm.height_m.assign(static_cast<size_t>(hm.rows) * hm.cols, 0.0f);
  for (const double inset_m : {0.015, 0.03, 0.07, 0.13}) {
    for (int trial = 0; trial < 6; ++trial) {
      LocalGrid mask;
      mask.row0 = 5;
      mask.col0 = 7;
      mask.rows = std::uniform_int_distribution<int>(20, 80)(rng);
      mask.cols = std::uniform_int_distribution<int>(20, 100)(rng);
      mask.cells.assign(static_cast<size_t>(mask.rows) * mask.cols, 1);
      std::bernoulli_distribution hole(0.01);
      for (uint8_t& cell : mask.cells) cell = hole(rng) ? 0 : 1;
      for (int r = 0; r < mask.rows; ++r) {  // a ragged right edge
        const int edge = mask.cols - std::uniform_int_distribution<int>(0, 6)(rng);
        for (int c = edge; c < mask.cols; ++c) mask.At(r, c) = 0;
      }
      PatchDecompositionOptions options;
      options.inset_m = inset_m;
      const InsetsInCells insets = InsetsToCells(options, res);
      const InsetField inset(hm, mask, options, insets);
      const std::vector<DiskOffset> offsets = DiskOffsets(insets.max, res);
      const LocalGrid expected = ErodedByEveryOffset(mask, inset, offsets, res);
      const LocalGrid eroded = ErodedMask(mask, inset, offsets, res);
      EXPECT_EQ(eroded.cells, expected.cells) << "inset " << inset_m << " trial " << trial;
      int kept = 0, lost = 0;
      for (size_t i = 0; i < mask.cells.size(); ++i) {
        kept += expected.cells[i];
        lost += mask.cells[i] && !expected.cells[i];
      }
      EXPECT_GT(kept, 0);
      EXPECT_GT(lost, 0);
    }
  }
}

}  // namespace
}  // namespace mfp
