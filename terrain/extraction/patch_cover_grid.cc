#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

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

// Moves the sides of rects[k] out by their slack (-x, +x, -y, +y, each with the sides
// moved so far); unless may_overlap, a side stops at the other rectangles beyond it when
// they span it (RoomBeforeOthers: the earlier ones with their slack, the later ones
// without), so neighbours that share a whole side do not overlap.
void AddSlack(const CoverInput& in, bool may_overlap, size_t k, std::vector<AxisRect>* rects) {
  const double max_inset = in.max_inset_cells;
  auto inset_xy = [&](int c, int r) { return in.inset->At(r, c); };
  auto room = [&](AxisRect::Side side) { return may_overlap ? INFINITY : RoomBeforeOthers(*rects, k, side); };
  AxisRect& r = (*rects)[k];
  r.x0 -= std::min(room(AxisRect::kMinusX), SideSlack(inset_xy, r.x0, r.y0, r.y1, max_inset));
  r.x1 += std::min(room(AxisRect::kPlusX),
                   SideSlack([&](int c, int rr) { return inset_xy(-c, rr); }, -r.x1, r.y0, r.y1, max_inset));
  r.y0 -= std::min(room(AxisRect::kMinusY),
                   SideSlack([&](int c, int rr) { return inset_xy(rr, c); }, r.y0, r.x0, r.x1, max_inset));
  r.y1 += std::min(room(AxisRect::kPlusY),
                   SideSlack([&](int c, int rr) { return inset_xy(rr, -c); }, -r.y1, r.x0, r.x1, max_inset));
}

}  // namespace

double RoomBeforeOthers(const std::vector<AxisRect>& rects, size_t k, AxisRect::Side side) {
  constexpr double kTouch = 1e-9;  // sides this close count as shared [units]
  const AxisRect& r = rects[k];
  const bool along_y = side == AxisRect::kMinusX || side == AxisRect::kPlusX;  // the side's own extent
  const double lo = along_y ? r.y0 : r.x0, hi = along_y ? r.y1 : r.x1;
  // Per rectangle beyond the side sharing a stretch of it: its gap and that stretch.
  struct Beyond {
    double gap, from, to;
  };
  std::vector<Beyond> beyond;
  for (size_t j = 0; j < rects.size(); ++j) {
    const AxisRect& o = rects[j];
    const double from = std::max(lo, along_y ? o.y0 : o.x0), to = std::min(hi, along_y ? o.y1 : o.x1);
    if (j == k || to - from <= kTouch) continue;
    double gap = INFINITY;
    if (side == AxisRect::kMinusX && o.x0 < r.x0 - kTouch) gap = r.x0 - o.x1;
    if (side == AxisRect::kPlusX && o.x1 > r.x1 + kTouch) gap = o.x0 - r.x1;
    if (side == AxisRect::kMinusY && o.y0 < r.y0 - kTouch) gap = r.y0 - o.y1;
    if (side == AxisRect::kPlusY && o.y1 > r.y1 + kTouch) gap = o.y0 - r.y1;
    if (gap < INFINITY) beyond.push_back({std::max(0.0, gap), from, to});
  }
  if (beyond.empty()) return INFINITY;
  const double nearest = std::min_element(beyond.begin(), beyond.end(), [](const Beyond& a, const Beyond& b) {
                           return a.gap < b.gap;
                         })->gap;
  // The nearest ones must span the whole side: then what the side would add past them
  // lies in them, and stopping there loses no floor. Otherwise the side moves on.
  std::vector<std::pair<double, double>> stretches;
  for (const Beyond& b : beyond) {
    if (b.gap <= nearest + kTouch) stretches.emplace_back(b.from, b.to);
  }
  std::sort(stretches.begin(), stretches.end());
  double reached = lo;
  for (const auto& [from, to] : stretches) {
    if (from > reached + kTouch) return INFINITY;
    reached = std::max(reached, to);
  }
  return reached >= hi - kTouch ? nearest : INFINITY;
}

// Rectangles of complete dual squares end on cell centres; each side then moves out as
// far as its strip keeps the inset from every cell outside the patch, so regions lose
// less than the cell quantisation of the inset.
std::vector<Quad2d> CoverOnGrid(const CoverInput& in, const PatchDecompositionOptions& options) {
  RectangleCoverOptions cover = options.cover;
  cover.min_rect_cells = MinRectCells(options.min_area_xy_m2, in.res * in.res);
  std::vector<AxisRect> rects;
  for (const CellRect& rect : GreedyRectangleCover(in.dual->cells, in.dual->rows, in.dual->cols, cover)) {
    rects.push_back({double(rect.col0), double(rect.col0 + rect.cols), double(rect.row0), double(rect.row0 + rect.rows)});
  }
  if (in.max_inset_cells > 0.0) {
    for (size_t k = 0; k < rects.size(); ++k) AddSlack(in, cover.grow_over_covered, k, &rects);
  }
  std::vector<Quad2d> quads;
  quads.reserve(rects.size());
  for (const AxisRect& r : rects) {
    quads.push_back({in.ToWorld({r.x0, r.y0}), in.ToWorld({r.x1, r.y0}), in.ToWorld({r.x1, r.y1}), in.ToWorld({r.x0, r.y1})});
  }
  return quads;
}

}  // namespace mfp
