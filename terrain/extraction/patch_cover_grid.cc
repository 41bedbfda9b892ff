#include <algorithm>
#include <cmath>

#include "terrain/extraction/internal/patch_cover.h"

namespace mfp {
namespace {

// How far (in cells) the side of a safe rectangle [x0, x1] x [y0, y1] (local centre
// units) facing -x can move out while the strip it sweeps stays at least each outside
// cell's inset from that cell's square: for a cell square [a0, a1] x [b0, b1] at
// distance dy across, the strip's end must keep sqrt(inset^2 - dy^2) along x. inset_at
// answers in the side's own frame (mirrored or transposed): the cell's inset in cells,
// negative for a patch cell; max_inset_cells bounds them all.
template <typename InsetAt>
double SideSlack(const InsetAt& inset_at, double x0, double y0, double y1, double max_inset_cells) {
  double s = 1.0;
  const int c_lo = static_cast<int>(std::floor(x0 - max_inset_cells - 2.0));
  const int c_hi = static_cast<int>(std::ceil(x0 + max_inset_cells + 1.0));
  const int r_lo = static_cast<int>(std::floor(y0 - max_inset_cells - 1.0));
  const int r_hi = static_cast<int>(std::ceil(y1 + max_inset_cells + 1.0));
  for (int r = r_lo; r <= r_hi; ++r) {
    const double dy = std::max({0.0, (r - 0.5) - y1, y0 - (r + 0.5)});
    if (dy >= max_inset_cells) continue;
    for (int c = c_lo; c <= c_hi; ++c) {
      const double inset_cells = inset_at(c, r);
      if (inset_cells < 0.0 || dy >= inset_cells) continue;
      const double h = std::sqrt(inset_cells * inset_cells - dy * dy);
      const double a0 = c - 0.5, a1 = c + 0.5;
      if (a0 - x0 >= h - 1e-12) continue;  // far enough on the rectangle's side
      s = std::min(s, x0 - a1 - h);
    }
  }
  return std::max(0.0, s);
}

}  // namespace

// Rectangles of complete dual squares end on cell centres; each side then moves out as
// far as its strip keeps the inset from every cell outside the patch, so regions lose
// less than the cell quantisation of the inset.
std::vector<Quad2d> CoverOnGrid(const CoverInput& in, const PatchDecompositionOptions& options) {
  RectangleCoverOptions cover = options.cover;
  cover.min_rect_cells = MinRectCells(options.min_area_xy_m2, in.res * in.res);
  const double max_inset = in.max_inset_cells;
  auto inset_xy = [&](int c, int r) { return in.inset->At(r, c); };
  std::vector<Quad2d> quads;
  for (const CellRect& rect : GreedyRectangleCover(in.dual->cells, in.dual->rows, in.dual->cols, cover)) {
    double x0 = rect.col0, x1 = rect.col0 + rect.cols;
    double y0 = rect.row0, y1 = rect.row0 + rect.rows;
    if (max_inset > 0.0) {
      // -x, +x (mirrored), -y and +y (transposed), each with the sides moved so far.
      x0 -= SideSlack(inset_xy, x0, y0, y1, max_inset);
      x1 += SideSlack([&](int c, int r) { return inset_xy(-c, r); }, -x1, y0, y1, max_inset);
      y0 -= SideSlack([&](int c, int r) { return inset_xy(r, c); }, y0, x0, x1, max_inset);
      y1 += SideSlack([&](int c, int r) { return inset_xy(r, -c); }, -y1, x0, x1, max_inset);
    }
    quads.push_back({in.ToWorld({x0, y0}), in.ToWorld({x1, y0}), in.ToWorld({x1, y1}), in.ToWorld({x0, y1})});
  }
  return quads;
}

}  // namespace mfp
