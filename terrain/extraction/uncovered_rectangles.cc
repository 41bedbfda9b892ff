#include "terrain/extraction/internal/uncovered_rectangles.h"

#include <algorithm>

#include "base/check.h"

namespace mfp {

UncoveredRectangles::UncoveredRectangles(const std::vector<uint8_t>& mask, int rows, int cols)
    : rows_(rows),
      cols_(cols),
      cells_(mask.size()),
      height_(mask.size(), 0),
      row_best_(static_cast<size_t>(std::max(rows, 0))),
      stale_(row_best_.size(), 0) {
  MFP_CHECK(rows >= 0 && cols >= 0 && mask.size() == static_cast<size_t>(rows) * static_cast<size_t>(cols));
  stack_.reserve(static_cast<size_t>(cols) + 1);
  active_.reserve(static_cast<size_t>(cols));
  for (size_t i = 0; i < mask.size(); ++i) cells_[i] = mask[i] ? 1 : 0;
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < cols_; ++c) {
      const size_t i = static_cast<size_t>(r) * cols_ + c;
      height_[i] = cells_[i] ? (r > 0 ? height_[i - cols_] : 0) + 1 : 0;
    }
    ScanRow(r);
  }
}

void UncoveredRectangles::ScanRow(int r) const {
  // The stack scan of LargestRectangle, over this row's histogram only, one run of set
  // columns at a time: a column of height 0 empties the stack (every height is >= 0) and
  // adds no area, so each run is scanned alone with its first column as the left end of
  // an empty stack, the same rectangles compared in the same order.
  CellRect best;
  const int* heights = &height_[static_cast<size_t>(r) * cols_];
  for (int c = 0; c < cols_;) {
    if (heights[c] == 0) {
      ++c;
      continue;
    }
    const int run_begin = c;
    while (c < cols_ && heights[c] != 0) ++c;
    const int run_end = c;
    stack_.clear();
    for (int k = run_begin; k <= run_end; ++k) {
      const int hk = k < run_end ? heights[k] : 0;  // the 0 after the run flushes the stack
      while (!stack_.empty() && heights[stack_.back()] >= hk) {
        const int h = heights[stack_.back()];
        stack_.pop_back();
        const int left = stack_.empty() ? run_begin : stack_.back() + 1;
        const int width = k - left;
        if (h * width > best.Area()) best = CellRect{r - h + 1, left, h, width};
      }
      stack_.push_back(k);
    }
  }
  row_best_[static_cast<size_t>(r)] = best;
}

CellRect UncoveredRectangles::Largest() const {
  // The largest fresh area, and the stale rows that could beat or tie it (their cached best
  // bounds theirs from above), highest bound first, then by row.
  int fresh_top = 0;
  candidates_.clear();
  for (int r = 0; r < rows_; ++r) {
    const int area = row_best_[static_cast<size_t>(r)].Area();
    if (!stale_[static_cast<size_t>(r)]) {
      fresh_top = std::max(fresh_top, area);
    } else if (area > 0) {
      candidates_.push_back(r);
    }
  }
  std::sort(candidates_.begin(), candidates_.end(), [&](int a, int b) {
    const int area_a = row_best_[static_cast<size_t>(a)].Area(), area_b = row_best_[static_cast<size_t>(b)].Area();
    return area_a != area_b ? area_a > area_b : a < b;
  });
  // Scan them while their bound reaches the largest area known: afterwards every row whose
  // value reaches it is fresh, so the first row holding the largest value is the first row
  // of the largest rectangle, as a scan of every row finds.
  for (const int r : candidates_) {
    if (row_best_[static_cast<size_t>(r)].Area() < fresh_top) break;
    ScanRow(r);
    stale_[static_cast<size_t>(r)] = 0;
    fresh_top = std::max(fresh_top, row_best_[static_cast<size_t>(r)].Area());
  }
  CellRect best;
  for (const CellRect& rect : row_best_) {
    if (rect.Area() > best.Area()) best = rect;
  }
  return best;
}

size_t UncoveredRectangles::Clear(const CellRect& rect) {
  MFP_CHECK(rect.row0 >= 0 && rect.col0 >= 0 && rect.rows >= 0 && rect.cols >= 0 &&
            rect.row0 + rect.rows <= rows_ && rect.col0 + rect.cols <= cols_);
  if (rect.Area() == 0) return 0;
  size_t cleared = 0;
  for (int r = rect.row0; r < rect.row0 + rect.rows; ++r) {
    for (int c = rect.col0; c < rect.col0 + rect.cols; ++c) {
      uint8_t& cell = cells_[static_cast<size_t>(r) * cols_ + c];
      cleared += cell;
      cell = 0;
    }
  }
  if (cleared == 0) return 0;
  // Heights change in the cleared columns from the first cleared row down, until a row
  // below the rectangle keeps its height (then every row below it keeps it too).
  active_.clear();
  for (int c = rect.col0; c < rect.col0 + rect.cols; ++c) active_.push_back(c);
  Recompute(rect.row0, rect.row0 + rect.rows - 1, nullptr, nullptr);
  return cleared;
}

size_t UncoveredRectangles::ClearCells(const std::vector<size_t>& indices) {
  if (first_cleared_.empty()) {
    first_cleared_.assign(static_cast<size_t>(cols_), -1);
    last_cleared_.assign(static_cast<size_t>(cols_), -1);
  }
  size_t cleared = 0;
  int from = rows_, to = -1;
  active_.clear();
  for (const size_t i : indices) {
    MFP_CHECK(i < cells_.size());
    if (!cells_[i]) continue;
    cells_[i] = 0;
    ++cleared;
    const int r = static_cast<int>(i / cols_), c = static_cast<int>(i % cols_);
    if (first_cleared_[c] < 0) {
      active_.push_back(c);
      first_cleared_[c] = last_cleared_[c] = r;
    }
    first_cleared_[c] = std::min(first_cleared_[c], r);
    last_cleared_[c] = std::max(last_cleared_[c], r);
    from = std::min(from, r);
    to = std::max(to, r);
  }
  if (cleared == 0) return 0;
  std::sort(active_.begin(), active_.end());
  const std::vector<int> columns = active_;
  Recompute(from, to, first_cleared_.data(), last_cleared_.data());
  for (const int c : columns) first_cleared_[c] = last_cleared_[c] = -1;
  return cleared;
}

void UncoveredRectangles::Recompute(int from, int to, const int* first, const int* last) {
  // Row by row (the array's order), over the columns still changing.
  int last_changed = to;
  for (int r = from; r < rows_ && !active_.empty(); ++r) {
    size_t kept = 0;
    for (const int c : active_) {
      if (first != nullptr && r < first[c]) {  // not cleared above this row: unchanged so far
        active_[kept++] = c;
        continue;
      }
      const size_t i = static_cast<size_t>(r) * cols_ + c;
      const int h = cells_[i] ? (r > 0 ? height_[i - cols_] : 0) + 1 : 0;
      if (r > (last != nullptr ? last[c] : to) && h == height_[i]) continue;  // this column keeps its heights below
      height_[i] = h;
      last_changed = std::max(last_changed, r);
      active_[kept++] = c;
    }
    active_.resize(kept);
  }
  for (int r = from; r <= last_changed; ++r) stale_[static_cast<size_t>(r)] = 1;
}

}  // namespace mfp
