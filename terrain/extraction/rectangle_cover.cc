#include "terrain/extraction/internal/rectangle_cover.h"

#include <algorithm>

#include "base/check.h"
#include "terrain/extraction/internal/uncovered_rectangles.h"

namespace mfp {

CellRect LargestRectangle(const std::vector<uint8_t>& mask, int rows, int cols) {
  return LargestRectangleWithin(mask, rows, cols, CellRect{0, 0, rows, cols});
}

CellRect LargestRectangleWithin(const std::vector<uint8_t>& mask, int rows, int cols, const CellRect& within) {
  MFP_CHECK(mask.size() == static_cast<size_t>(rows) * static_cast<size_t>(cols));
  MFP_CHECK(within.row0 >= 0 && within.col0 >= 0 && within.rows >= 0 && within.cols >= 0 &&
            within.row0 + within.rows <= rows && within.col0 + within.cols <= cols);
  // Row by row: heights of the runs of set cells ending at this row, then the largest
  // rectangle under that histogram with a stack (O(rows * cols) overall).
  CellRect best;
  const int n = within.cols;
  std::vector<int> height(static_cast<size_t>(n) + 1, 0);
  std::vector<int> stack;
  stack.reserve(static_cast<size_t>(n) + 1);
  for (int r = within.row0; r < within.row0 + within.rows; ++r) {
    const uint8_t* row = &mask[static_cast<size_t>(r) * cols + within.col0];
    for (int c = 0; c < n; ++c) height[c] = row[c] ? height[c] + 1 : 0;
    height[n] = 0;  // sentinel flushes the stack
    stack.clear();
    for (int c = 0; c <= n; ++c) {
      while (!stack.empty() && height[stack.back()] >= height[c]) {
        const int h = height[stack.back()];
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        const int width = c - left;
        if (h * width > best.Area()) best = CellRect{r - h + 1, within.col0 + left, h, width};
      }
      stack.push_back(c);
    }
  }
  return best;
}

namespace {

bool RowInside(const std::vector<uint8_t>& mask, int cols, int r, int c0, int n) {
  for (int c = c0; c < c0 + n; ++c) {
    if (!mask[static_cast<size_t>(r) * cols + c]) return false;
  }
  return true;
}

bool ColInside(const std::vector<uint8_t>& mask, int cols, int c, int r0, int n) {
  for (int r = r0; r < r0 + n; ++r) {
    if (!mask[static_cast<size_t>(r) * cols + c]) return false;
  }
  return true;
}

// Adds the row (along_rows) or column just before or after the rectangle when it lies
// inside the mask; true when it did.
bool GrowSide(const std::vector<uint8_t>& mask, int rows, int cols, bool along_rows, bool before,
              CellRect* rect) {
  int& start = along_rows ? rect->row0 : rect->col0;
  int& extent = along_rows ? rect->rows : rect->cols;
  const int line = before ? start - 1 : start + extent;
  if (line < 0 || line >= (along_rows ? rows : cols)) return false;
  const bool inside = along_rows ? RowInside(mask, cols, line, rect->col0, rect->cols)
                                 : ColInside(mask, cols, line, rect->row0, rect->rows);
  if (!inside) return false;
  if (before) --start;
  ++extent;
  return true;
}

// Grows a rectangle one row or column at a time while it stays inside the mask: rows
// before and after, then columns before and after, round after round.
void GrowInside(const std::vector<uint8_t>& mask, int rows, int cols, CellRect* rect) {
  bool grew = true;
  while (grew) {
    grew = false;
    for (const bool along_rows : {true, false}) {
      for (const bool before : {true, false}) grew |= GrowSide(mask, rows, cols, along_rows, before, rect);
    }
  }
}

int Find(std::vector<int>* parent, int i) {
  while ((*parent)[i] != i) i = (*parent)[i] = (*parent)[(*parent)[i]];
  return i;
}

// Per cell, the last rectangle holding it (-1: none).
std::vector<int> RectOwners(const std::vector<CellRect>& rects, int rows, int cols) {
  std::vector<int> owner(static_cast<size_t>(rows) * cols, -1);
  for (size_t k = 0; k < rects.size(); ++k) {
    const CellRect& rect = rects[k];
    for (int r = rect.row0; r < rect.row0 + rect.rows; ++r) {
      for (int c = rect.col0; c < rect.col0 + rect.cols; ++c) owner[static_cast<size_t>(r) * cols + c] = static_cast<int>(k);
    }
  }
  return owner;
}

}  // namespace

std::vector<uint8_t> UncoveredBridge(const std::vector<uint8_t>& uncovered, const std::vector<int>& owner, int rows,
                                     int cols, CellRect* bounds) {
  const size_t n = static_cast<size_t>(rows) * cols;
  MFP_CHECK(uncovered.size() == n && owner.size() == n);
  const int pieces = owner.empty() ? 0 : *std::max_element(owner.begin(), owner.end()) + 1;
  std::vector<int> parent(static_cast<size_t>(std::max(0, pieces)));
  for (size_t k = 0; k < parent.size(); ++k) parent[k] = static_cast<int>(k);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int a = owner[static_cast<size_t>(r) * cols + c];
      if (a < 0) continue;
      if (c + 1 < cols && owner[static_cast<size_t>(r) * cols + c + 1] >= 0) {
        parent[Find(&parent, a)] = Find(&parent, owner[static_cast<size_t>(r) * cols + c + 1]);
      }
      if (r + 1 < rows && owner[static_cast<size_t>(r + 1) * cols + c] >= 0) {
        parent[Find(&parent, a)] = Find(&parent, owner[static_cast<size_t>(r + 1) * cols + c]);
      }
    }
  }
  std::vector<uint8_t> seen(n, 0), piece;
  std::vector<size_t> stack, cells;
  for (size_t start = 0; start < n; ++start) {
    if (!uncovered[start] || seen[start]) continue;
    cells.clear();
    stack = {start};
    seen[start] = 1;
    int first_root = -1;
    bool bridge = false;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      cells.push_back(i);
      const int r = static_cast<int>(i / cols), c = static_cast<int>(i % cols);
      const int dr[4] = {-1, 1, 0, 0}, dc[4] = {0, 0, -1, 1};
      for (int d = 0; d < 4; ++d) {
        const int rr = r + dr[d], cc = c + dc[d];
        if (rr < 0 || rr >= rows || cc < 0 || cc >= cols) continue;
        const size_t j = static_cast<size_t>(rr) * cols + cc;
        if (owner[j] >= 0) {
          const int root = Find(&parent, owner[j]);
          if (first_root < 0) first_root = root;
          bridge |= root != first_root;
        } else if (uncovered[j] && !seen[j]) {
          seen[j] = 1;
          stack.push_back(j);
        }
      }
    }
    if (!bridge) continue;
    piece.assign(n, 0);
    int r0 = rows, r1 = -1, c0 = cols, c1 = -1;
    for (size_t i : cells) {
      piece[i] = 1;
      const int r = static_cast<int>(i / cols), c = static_cast<int>(i % cols);
      r0 = std::min(r0, r), r1 = std::max(r1, r), c0 = std::min(c0, c), c1 = std::max(c1, c);
    }
    if (bounds != nullptr) *bounds = CellRect{r0, c0, r1 - r0 + 1, c1 - c0 + 1};
    return piece;
  }
  return piece;
}

std::vector<CellRect> GreedyRectangleCover(const std::vector<uint8_t>& mask, int rows, int cols,
                                           const RectangleCoverOptions& options) {
  MFP_CHECK(mask.size() == static_cast<size_t>(rows) * static_cast<size_t>(cols));
  UncoveredRectangles uncovered(mask, rows, cols);
  size_t total = 0;
  for (uint8_t m : mask) total += m ? 1 : 0;
  size_t left = total;
  std::vector<CellRect> rects;
  auto more = [&] { return left > 0 && static_cast<int>(rects.size()) < options.max_rects && !options.deadline.Expired(); };
  while (more() && static_cast<double>(total - left) < options.target_coverage * static_cast<double>(total)) {
    CellRect rect = uncovered.Largest();
    if (rect.Area() < std::max(1, options.min_rect_cells)) break;
    if (options.grow_over_covered) GrowInside(mask, rows, cols, &rect);
    left -= uncovered.Clear(rect);
    rects.push_back(rect);
  }
  // Covered enough, but the part left may hold the only way between two pieces of the
  // cover (a wall's opening, a few per cent of a floor): cover those too.
  while (options.connect_pieces && more()) {
    CellRect bounds;
    const std::vector<uint8_t> bridge =
        UncoveredBridge(uncovered.cells(), RectOwners(rects, rows, cols), rows, cols, &bounds);
    if (bridge.empty()) break;
    CellRect rect = LargestRectangleWithin(bridge, rows, cols, bounds);
    if (rect.Area() < std::max(1, options.min_rect_cells)) break;
    if (options.grow_over_covered) GrowInside(mask, rows, cols, &rect);
    left -= uncovered.Clear(rect);
    rects.push_back(rect);
  }
  return rects;
}

}  // namespace mfp
