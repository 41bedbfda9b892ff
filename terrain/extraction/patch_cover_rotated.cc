#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "geometry/convex_polygon_distance.h"
#include "terrain/extraction/internal/patch_cover.h"

namespace mfp {
namespace {

// The rotated grid: u along the principal direction, v across, in steps of half a cell,
// spanning the dual squares' bounding box.
struct RotatedFrame {
  static constexpr double kStep = 0.5;
  Eigen::Vector2d eu, ev;
  double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;

  RotatedFrame(double angle, const LocalGrid& dual)
      : eu(std::cos(angle), std::sin(angle)), ev(-std::sin(angle), std::cos(angle)) {
    for (double x : {0.0, double(dual.cols)}) {
      for (double y : {0.0, double(dual.rows)}) {
        const Eigen::Vector2d p(x, y);
        umin = std::min(umin, p.dot(eu));
        umax = std::max(umax, p.dot(eu));
        vmin = std::min(vmin, p.dot(ev));
        vmax = std::max(vmax, p.dot(ev));
      }
    }
  }
  // Rotated-grid corner -> centre units.
  Eigen::Vector2d Corner(double a, double b) const {
    return Eigen::Vector2d(eu * (umin + a * kStep) + ev * (vmin + b * kStep));
  }
};

struct Box2d {
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  void Add(const Eigen::Vector2d& p) {
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
};

// A rotated-grid cell is kept when its bounding box lies in complete dual squares.
LocalGrid RotatedGrid(const RotatedFrame& frame, const LocalGrid& dual) {
  LocalGrid rotated;
  rotated.cols = static_cast<int>(std::ceil((frame.umax - frame.umin) / RotatedFrame::kStep));
  rotated.rows = static_cast<int>(std::ceil((frame.vmax - frame.vmin) / RotatedFrame::kStep));
  rotated.cells.assign(static_cast<size_t>(rotated.rows) * rotated.cols, 0);
  // The lattice points of rows b and b + 1, each computed once (Corner's own arithmetic).
  std::vector<Eigen::Vector2d> lower(static_cast<size_t>(rotated.cols) + 1), upper(lower.size());
  for (int a = 0; a <= rotated.cols; ++a) upper[static_cast<size_t>(a)] = frame.Corner(a, 0);
  for (int b = 0; b < rotated.rows; ++b) {
    lower.swap(upper);
    for (int a = 0; a <= rotated.cols; ++a) upper[static_cast<size_t>(a)] = frame.Corner(a, b + 1);
    for (int a = 0; a < rotated.cols; ++a) {
      const auto k = static_cast<size_t>(a);
      // The dual square holding the cell's centre is one of those its box spans (the centre
      // lies at least a quarter of a cell inside the box): when it is not a complete dual
      // square, or off the grid, the cell is not kept, and the box need not be computed.
      const Eigen::Vector2d centre = 0.25 * (lower[k] + lower[k + 1] + upper[k] + upper[k + 1]);
      const int centre_c = static_cast<int>(std::floor(centre.x())), centre_r = static_cast<int>(std::floor(centre.y()));
      if (!dual.Contains(centre_r, centre_c)) continue;
      Box2d box;
      for (const Eigen::Vector2d& p : {lower[k], lower[k + 1], upper[k], upper[k + 1]}) box.Add(p);
      const int c0 = static_cast<int>(std::floor(box.xmin + 1e-9));
      const int c1 = static_cast<int>(std::ceil(box.xmax - 1e-9));
      const int r0 = static_cast<int>(std::floor(box.ymin + 1e-9));
      const int r1 = static_cast<int>(std::ceil(box.ymax - 1e-9));
      if (c0 < 0 || r0 < 0 || c1 > dual.cols || r1 > dual.rows) continue;
      bool inside = true;
      for (int r = r0; r < r1 && inside; ++r) {
        for (int c = c0; c < c1 && inside; ++c) inside = dual.At(r, c);
      }
      rotated.At(b, a) = inside;
    }
  }
  return rotated;
}

// A cell outside the patch near it (holes, and a ring around the bounding box), with its
// inset.
struct OutsideCell {
  int r, c;
  double inset_cells;
};

// The outside cells row by row (rows from -ring, each in column order) in one list, so
// a test near a rectangle visits only the rows and columns within reach of it.
struct OutsideCells {
  int row0 = 0;
  std::vector<OutsideCell> cells;
  std::vector<size_t> row_begin;  // row i's cells are cells[row_begin[i], row_begin[i + 1])
  int rows() const { return static_cast<int>(row_begin.size()) - 1; }
};

OutsideCells ListOutsideCells(const LocalGrid& mask, const InsetField& inset) {
  OutsideCells outside;
  outside.row0 = -inset.ring();
  outside.row_begin.reserve(static_cast<size_t>(mask.rows + 2 * inset.ring()) + 1);
  outside.row_begin.push_back(0);
  for (int r = -inset.ring(); r < mask.rows + inset.ring(); ++r) {
    for (int c = -inset.ring(); c < mask.cols + inset.ring(); ++c) {
      if (mask.Contains(r, c)) continue;
      outside.cells.push_back({r, c, inset.At(r, c)});
    }
    outside.row_begin.push_back(outside.cells.size());
  }
  return outside;
}

// From the cell's centre to the nearest point of the rectangle [u0, u1] x [v0, v1], along
// the rotated grid's axes [rotated-grid steps] (0, 0 inside it).
struct TowardRectangle {
  double along, across;
};

TowardRectangle OffsetToRectangle(const RotatedFrame& frame, const OutsideCell& out, double u0, double u1, double v0,
                                  double v1) {
  const double step = RotatedFrame::kStep;
  const Eigen::Vector2d centre(out.c, out.r);
  const double a = (centre.dot(frame.eu) - frame.umin) / step, bb = (centre.dot(frame.ev) - frame.vmin) / step;
  return {a < u0 ? u0 - a : a > u1 ? u1 - a : 0.0, bb < v0 ? v0 - bb : bb > v1 ? v1 - bb : 0.0};
}

// What TooClose's cheap bounds compare: the distance [cells] from the cell's centre to the
// rectangle.
double CentreDistance(const TowardRectangle& toward) {
  return RotatedFrame::kStep * std::hypot(toward.along, toward.across);
}

double CentreDistance(const RotatedFrame& frame, const OutsideCell& out, double u0, double u1, double v0, double v1) {
  return CentreDistance(OffsetToRectangle(frame, out, u0, u1, v0, v1));
}

// How far the cell's square reaches from its centre toward the rectangle [cells]: with u the
// unit vector from the centre to the rectangle's nearest point, the square's largest u . q
// about its centre, (|u.x| + |u.y|) / 2 (half a diagonal at most). The rectangle lies beyond
// the line through that point across u, so it keeps at least the centre distance less this
// from the square.
double SquareReachToward(const RotatedFrame& frame, const TowardRectangle& toward) {
  const Eigen::Vector2d u = toward.along * frame.eu + toward.across * frame.ev;
  const double length = u.norm();
  if (!(length > 0.0)) return std::sqrt(0.5);  // inside the rectangle: any direction
  return 0.5 * (std::abs(u.x()) + std::abs(u.y())) / length;
}

// Half a cell's diagonal, rounded up: a cell square lies within this of its centre [cells].
constexpr double kHalfDiagonal = 0.7072;

// Whether the rectangle [u0, u1] x [v0, v1] (its corners `quad`) keeps `out`'s inset from
// the cell's square (false) or not (true): bounds by the centre's distance, then exactly.
bool TooClose(const RotatedFrame& frame, const std::array<Eigen::Vector2d, 4>& quad, const OutsideCell& out, double u0,
              double u1, double v0, double v1) {
  const TowardRectangle toward = OffsetToRectangle(frame, out, u0, u1, v0, v1);
  const double centre_dist = CentreDistance(toward);
  if (centre_dist >= out.inset_cells + kHalfDiagonal) return false;
  if (centre_dist < out.inset_cells - kHalfDiagonal) return true;
  // Clear by the square's reach toward the rectangle, with a margin far above the
  // distances' rounding (the exact test below then answers false as well).
  constexpr double kMargin = 1e-6;  // [cells]
  if (centre_dist - SquareReachToward(frame, toward) >= out.inset_cells + kMargin) return false;
  const int r = out.r, c = out.c;
  const std::array<Eigen::Vector2d, 4> cell = {Eigen::Vector2d(c - 0.5, r - 0.5), Eigen::Vector2d(c + 0.5, r - 0.5),
                                               Eigen::Vector2d(c + 0.5, r + 0.5), Eigen::Vector2d(c - 0.5, r + 0.5)};
  return ConvexPolygonsNearer(quad, cell, out.inset_cells - 1e-9);
}

std::array<Eigen::Vector2d, 4> RectQuad(const RotatedFrame& frame, double u0, double u1, double v0, double v1) {
  return {frame.Corner(u0, v0), frame.Corner(u1, v0), frame.Corner(u1, v1), frame.Corner(u0, v1)};
}

// Calls visit(cell) for every outside cell within `reach` cells of the rectangle's bounding
// box (and some beyond), row by row, until it returns false; false then.
template <typename Visit>
bool ForCellsNear(const OutsideCells& outside, const std::array<Eigen::Vector2d, 4>& quad, double reach,
                  Visit&& visit) {
  Box2d box;
  for (const Eigen::Vector2d& p : quad) box.Add(p);
  const int first = std::max(0, static_cast<int>(std::ceil(box.ymin - reach)) - outside.row0);
  const int last = std::min(outside.rows() - 1, static_cast<int>(std::floor(box.ymax + reach)) - outside.row0);
  for (int i = first; i <= last; ++i) {
    const auto row_begin = outside.cells.begin() + static_cast<std::ptrdiff_t>(outside.row_begin[static_cast<size_t>(i)]);
    const auto row_end = outside.cells.begin() + static_cast<std::ptrdiff_t>(outside.row_begin[static_cast<size_t>(i) + 1]);
    auto it = std::lower_bound(row_begin, row_end, box.xmin - reach,
                               [](const OutsideCell& cell, double x) { return cell.c < x; });
    for (; it != row_end && it->c <= box.xmax + reach; ++it) {
      if (!visit(*it)) return false;
    }
  }
  return true;
}

// Whether the rotated rectangle [u0, u1] x [v0, v1] (rotated-grid steps) keeps the inset
// from every cell square outside the patch: an exact test.
bool RotatedRectSafe(const RotatedFrame& frame, const OutsideCells& outside, double max_inset_cells, double u0,
                     double u1, double v0, double v1) {
  const std::array<Eigen::Vector2d, 4> quad = RectQuad(frame, u0, u1, v0, v1);
  // Cells further than the largest inset plus a cell from the box cannot be too close.
  return ForCellsNear(outside, quad, max_inset_cells + 1, [&](const OutsideCell& out) {
    return !TooClose(frame, quad, out, u0, u1, v0, v1);
  });
}

// The outside cells that may be too close to a rectangle inside [u0, u1] x [v0, v1]: every
// other cell's centre is further from the outer rectangle than its inset plus half a
// diagonal and a margin, so (the centre distance only growing as the rectangle shrinks, up
// to rounding far below the margin) TooClose's first bound clears it for any rectangle
// inside. The scan reaches a cell further than RotatedRectSafe's, so it holds every cell
// that test would visit for a rectangle inside.
void CellsThatMayBeTooClose(const RotatedFrame& frame, const OutsideCells& outside, double max_inset_cells,
                            double u0, double u1, double v0, double v1, std::vector<const OutsideCell*>* near) {
  constexpr double kMargin = 1e-6;  // [cells], far above the bounds' rounding
  near->clear();
  ForCellsNear(outside, RectQuad(frame, u0, u1, v0, v1), max_inset_cells + 2, [&](const OutsideCell& out) {
    if (CentreDistance(frame, out, u0, u1, v0, v1) < out.inset_cells + kHalfDiagonal + kMargin) near->push_back(&out);
    return true;
  });
}

// RotatedRectSafe for a rectangle inside the one `near` was listed for. The cell at
// *first (when in range) is tested first, and a cell found too close is left there: the
// one that failed a bisection step is the likeliest to fail the next (the answer is the
// same in any order).
bool RotatedRectSafeAmong(const RotatedFrame& frame, const std::vector<const OutsideCell*>& near, double u0, double u1,
                          double v0, double v1, size_t* first) {
  const std::array<Eigen::Vector2d, 4> quad = RectQuad(frame, u0, u1, v0, v1);
  auto too_close = [&](size_t k) { return TooClose(frame, quad, *near[k], u0, u1, v0, v1); };
  if (*first < near.size() && too_close(*first)) return false;
  for (size_t k = 0; k < near.size(); ++k) {
    if (k == *first || !too_close(k)) continue;
    *first = k;
    return false;
  }
  return true;
}

// Each side of a safe rotated rectangle moves out (in rotated-grid steps, up to one cell)
// while the rectangle stays safe, by bisection; each side's tests visit only the cells
// that may be too close to the rectangle with that side moved out the whole cell.
void GrowRotatedRect(const RotatedFrame& frame, const OutsideCells& outside,
                     double max_inset_cells, double* a0, double* a1, double* b0, double* b1) {
  const double most = 1.0 / RotatedFrame::kStep;  // one cell, in rotated-grid steps
  std::vector<const OutsideCell*> near;
  auto grow = [&](double* side, double sign) {
    double lo = 0.0, hi = most;
    const double base = *side;
    *side = base + sign * most;
    CellsThatMayBeTooClose(frame, outside, max_inset_cells, *a0, *a1, *b0, *b1, &near);
    size_t first = near.size();  // none yet
    for (int it = 0; it < 8; ++it) {
      const double mid = 0.5 * (lo + hi);
      *side = base + sign * mid;
      (RotatedRectSafeAmong(frame, near, *a0, *a1, *b0, *b1, &first) ? lo : hi) = mid;
    }
    *side = base + sign * lo;
  };
  grow(a0, -1.0);
  grow(a1, 1.0);
  grow(b0, -1.0);
  grow(b1, 1.0);
}

}  // namespace

std::vector<Quad2d> CoverRotated(const CoverInput& in, double angle, const PatchDecompositionOptions& options) {
  const RotatedFrame frame(angle, *in.dual);
  const LocalGrid rotated = RotatedGrid(frame, *in.dual);
  const OutsideCells outside = ListOutsideCells(*in.mask, *in.inset);
  RectangleCoverOptions cover = options.cover;
  const double step = RotatedFrame::kStep;
  cover.min_rect_cells = MinRectCells(options.min_area_xy_m2, step * step * in.res * in.res);
  std::vector<Quad2d> quads;
  for (const CellRect& rect : GreedyRectangleCover(rotated.cells, rotated.rows, rotated.cols, cover)) {
    double a0 = rect.col0, a1 = rect.col0 + rect.cols;
    double b0 = rect.row0, b1 = rect.row0 + rect.rows;
    if (in.max_inset_cells > 0.0 && RotatedRectSafe(frame, outside, in.max_inset_cells, a0, a1, b0, b1)) {
      GrowRotatedRect(frame, outside, in.max_inset_cells, &a0, &a1, &b0, &b1);
    }
    quads.push_back({in.ToWorld(frame.Corner(a0, b0)), in.ToWorld(frame.Corner(a1, b0)),
                     in.ToWorld(frame.Corner(a1, b1)), in.ToWorld(frame.Corner(a0, b1))});
  }
  return quads;
}

}  // namespace mfp
