#pragma once
// The largest rectangle of a binary cell mask, kept up to date while rectangles of it are
// cleared: what a greedy rectangle cover asks once per rectangle. Recomputing the largest
// rectangle over the whole mask costs O(rows * cols) per rectangle; here a clear recomputes
// the heights of only the rows it changed (the cleared rows, and below them the rows until
// each cleared column's run is broken) and marks those rows stale, and the answer is the
// best of the rows' cached bests. A stale row's cached best bounds its own from above
// (cells only clear), so a row is scanned again only when its bound could win: a row
// changed by many clears before it matters is scanned once. The answer is the rectangle LargestRectangle (rectangle_cover.h) returns on
// the same cells, ties included: the first of the largest in its row-by-row scan.
// Private to the extraction library.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrain/extraction/internal/rectangle_cover.h"

namespace mfp {

class UncoveredRectangles {
 public:
  // mask is row-major rows x cols, non-zero = set.
  UncoveredRectangles(const std::vector<uint8_t>& mask, int rows, int cols);

  // The largest rectangle of set cells (area 0 when none is set). Scans the stale rows
  // that could hold it (a cache: the answer does not depend on when rows are scanned).
  // Not thread-safe even as const: it updates the mutable row cache (one object per cover).
  CellRect Largest() const;

  // Clears the rectangle's cells (it must lie in the grid); returns how many were set.
  size_t Clear(const CellRect& rect);

  // Clears the cells at these row-major indices (any shape); returns how many were set.
  size_t ClearCells(const std::vector<size_t>& indices);

  // The cells still set (1) or not (0).
  const std::vector<uint8_t>& cells() const { return cells_; }

 private:
  // The first largest rectangle whose bottom row is r (LargestRectangle's scan of that row).
  void ScanRow(int r) const;

  int rows_, cols_;
  std::vector<uint8_t> cells_;
  std::vector<int> height_;     // per cell: set cells in its column ending at it
  mutable std::vector<CellRect> row_best_;  // per row, its best; for a stale row an upper bound
  mutable std::vector<uint8_t> stale_;      // per row, 1 when its heights changed since its scan
  mutable std::vector<int> stack_;          // ScanRow's work space
  mutable std::vector<int> candidates_;     // Largest's work space: stale rows
  std::vector<int> active_;  // Clear's work space: the columns whose heights still change
  std::vector<int> first_cleared_, last_cleared_;  // ClearCells' work space: per column, -1 when none
  // Recomputes the heights of the active columns from row `from` down (column c from row
  // first[c], until a row below last[c] keeps its height), then marks the changed rows stale.
  void Recompute(int from, int to, const int* first, const int* last);
};

}  // namespace mfp
