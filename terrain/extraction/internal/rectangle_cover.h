#pragma once
// Greedy cover of a binary cell mask by axis-aligned rectangles lying wholly inside it:
// repeatedly take the largest rectangle of not-yet-covered cells, then grow it over
// covered cells while it stays inside the mask (overlap helps a footstep move from one
// region to the next). Rectangles of mask cells are convex and hold only mask cells,
// which a convex hull of a non-convex mask would not.
#include <cstdint>
#include <vector>

#include "base/deadline.h"

namespace mfp {

struct CellRect {
  int row0 = 0, col0 = 0;  // first cell
  int rows = 0, cols = 0;  // extent in cells
  int Area() const { return rows * cols; }
};

struct RectangleCoverOptions {
  double target_coverage = 0.97;  // stop once this fraction of the mask is covered
  int min_rect_cells = 1;         // stop when the largest new rectangle is smaller
  int max_rects = 16;             // and never return more than this
  // Grow each rectangle over cells already covered (overlapping rectangles); false: the
  // rectangles only share sides, so a point lies in one of them but on a shared side.
  bool grow_over_covered = true;
  // After the target coverage, keep covering uncovered pieces that touch two pieces of the
  // cover that do not touch each other (a mask's necks), up to max_rects.
  bool connect_pieces = true;
  // Checked before each new piece: an expired one ends the cover early (what it holds is
  // still sound, only less is covered).
  Deadline deadline;
};

// mask is row-major rows x cols, non-zero = inside.
std::vector<CellRect> GreedyRectangleCover(const std::vector<uint8_t>& mask, int rows, int cols,
                                           const RectangleCoverOptions& options);

// The cells of one 4-connected piece of `uncovered` that touches two or more pieces of a
// cover that do not touch each other (a neck of the mask, such as the opening past a
// wall, that the cover left out); empty when there is none. owner: per cell, the cover's
// piece holding it, -1 when none; pieces touch when their cells are 4-neighbours.
// bounds (optional): the piece's bounding rectangle.
std::vector<uint8_t> UncoveredBridge(const std::vector<uint8_t>& uncovered, const std::vector<int>& owner, int rows,
                                     int cols, CellRect* bounds = nullptr);

// The largest rectangle of non-zero cells (area 0 when there is none); of those as large,
// the first the row-by-row stack scan meets.
CellRect LargestRectangle(const std::vector<uint8_t>& mask, int rows, int cols);

// LargestRectangle of a mask whose non-zero cells all lie in `within`, scanning only
// those cells: the same rectangle (the zero rows above and columns beside `within` add
// no rectangle and leave the scan's order inside it as it is).
CellRect LargestRectangleWithin(const std::vector<uint8_t>& mask, int rows, int cols, const CellRect& within);

}  // namespace mfp
