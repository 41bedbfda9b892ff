#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "geometry/convex_polygon_distance.h"
#include "geometry/half_plane_clip.h"
#include "terrain/extraction/internal/convex_cover.h"

namespace mfp {
namespace {

constexpr double kEps = 1e-9;  // rounding allowance [cells]

struct Bounds {
  Eigen::Vector2d lo, hi;
  bool Meets(const Bounds& o) const {
    return lo.x() < o.hi.x() && o.lo.x() < hi.x() && lo.y() < o.hi.y() && o.lo.y() < hi.y();
  }
};

Bounds BoundsOf(const Polygon2d& polygon) {
  Bounds b{polygon.front(), polygon.front()};
  for (const Eigen::Vector2d& p : polygon) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

// An edge's outward unit normal and offset: the polygon lies where normal . x <= offset.
struct HalfPlane {
  Eigen::Vector2d normal;
  double offset;
};

std::vector<HalfPlane> HalfPlanesOf(const Polygon2d& polygon) {
  std::vector<HalfPlane> planes;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - polygon[i];
    const double length = e.norm();
    if (length < 1e-12) {
      planes.push_back({Eigen::Vector2d::Zero(), 0.0});  // a degenerate edge: no constraint
      continue;
    }
    const Eigen::Vector2d n(e.y() / length, -e.x() / length);
    planes.push_back({n, n.dot(polygon[i])});
  }
  return planes;
}

// `polygon` clipped by the half-planes [begin, end) in order, edge `moved` pushed out by
// `shift` (`scratch`: the caller's work space).
void ClipBy(const std::vector<HalfPlane>& planes, size_t begin, size_t end, size_t moved, double shift,
            Polygon2d* polygon, Polygon2d* scratch) {
  for (size_t j = begin; j < end && polygon->size() >= 3; ++j) {
    if (planes[j].normal.isZero()) continue;
    KeepBelowLineInto(*polygon, planes[j].normal, planes[j].offset + (j == moved ? shift : 0.0), scratch);
    std::swap(*polygon, *scratch);
  }
}

// The polygon's half-planes with edge `moved` pushed out by `shift`, within `box`, into
// `polygon` (`scratch`: the caller's work space).
void Intersection(const std::vector<HalfPlane>& planes, size_t moved, double shift, const Bounds& box, Polygon2d* polygon,
                  Polygon2d* scratch) {
  *polygon = {box.lo, {box.hi.x(), box.lo.y()}, box.hi, {box.lo.x(), box.hi.y()}};
  ClipBy(planes, 0, planes.size(), moved, shift, polygon, scratch);
}

// Whether two convex polygons' interiors are apart: some edge of either separates them.
// (HalfPlanesOf's edges, taken one at a time.)
bool InteriorsApart(const Polygon2d& p, const Polygon2d& q) {
  for (const Polygon2d* a : {&p, &q}) {
    const Polygon2d* b = a == &p ? &q : &p;
    for (size_t i = 0; i < a->size(); ++i) {
      const Eigen::Vector2d e = (*a)[(i + 1) % a->size()] - (*a)[i];
      const double length = e.norm();
      if (length < 1e-12) continue;  // a degenerate edge: no constraint
      const Eigen::Vector2d n(e.y() / length, -e.x() / length);
      const double offset = n.dot((*a)[i]);
      double lowest = INFINITY;
      for (const Eigen::Vector2d& v : *b) lowest = std::min(lowest, n.dot(v) - offset);
      if (lowest >= -kEps) return true;
    }
  }
  return false;
}

// An outside cell (its square spanning [c - 0.5, c + 0.5] x [r - 0.5, r + 0.5]) and the
// inset it asks [cells].
struct InsetCell {
  int r = 0, c = 0;
  double inset = 0.0;
};

// Whether cell (r, c)'s square lies at least `inset` from the box b: then no part inside
// b comes nearer. Squared with a relative margin of 1e-12, so a cell cleared here is one the
// exact distance would pass as well.
bool BoundsClearCell(const Bounds& b, int r, int c, double inset) {
  const double dy = std::max({0.0, (r - 0.5) - b.hi.y(), b.lo.y() - (r + 0.5)});
  const double dx = std::max({0.0, (c - 0.5) - b.hi.x(), b.lo.x() - (c + 0.5)});
  return dx * dx + dy * dy >= inset * inset * (1.0 + 1e-12);
}

// Whether cell's square is nearer `part` than its inset, the part's bounds b: first by the
// bounds (far enough apart: not too close), then exactly.
bool TooClose(const Polygon2d& part, const Bounds& b, const InsetCell& cell) {
  const int r = cell.r, c = cell.c;
  if (BoundsClearCell(b, r, c, cell.inset)) return false;
  const std::array<Eigen::Vector2d, 4> square = {
      Eigen::Vector2d(c - 0.5, r - 0.5), Eigen::Vector2d(c + 0.5, r - 0.5), Eigen::Vector2d(c + 0.5, r + 0.5),
      Eigen::Vector2d(c - 0.5, r + 0.5)};
  return ConvexPolygonsNearer(part, square, cell.inset - kEps);
}

// Calls visit(cell) for each outside cell (inset > 0) within max_inset_cells + 0.5 of
// `box`, row by row, until visit returns false, and says whether none did. Cells farther
// away lie beyond their inset of any part inside the box (BoundsClearCell).
template <typename Visit>
bool ForOutsideCellsNear(const Bounds& box, const CellInset& inset_at, double max_inset_cells, Visit visit) {
  const double reach = max_inset_cells + 0.5;
  const int r0 = static_cast<int>(std::floor(box.lo.y() - reach)), r1 = static_cast<int>(std::ceil(box.hi.y() + reach));
  const int c0 = static_cast<int>(std::floor(box.lo.x() - reach)), c1 = static_cast<int>(std::ceil(box.hi.x() + reach));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const double inset = inset_at(r, c);
      if (inset > 0.0 && !visit(InsetCell{r, c, inset})) return false;  // inset <= 0: a patch cell, or none asked
    }
  }
  return true;
}

// The outside cells that some part with bounds inside `box` may come nearer than their
// inset: those TooClose's bounds test does not clear against the box (a part inside it is
// no nearer to any other cell).
std::vector<InsetCell> CellsNear(const Bounds& box, const CellInset& inset_at, double max_inset_cells) {
  std::vector<InsetCell> cells;
  ForOutsideCellsNear(box, inset_at, max_inset_cells, [&](const InsetCell& cell) {
    if (!BoundsClearCell(box, cell.r, cell.c, cell.inset)) cells.push_back(cell);
    return true;
  });
  return cells;
}

// Whether every point of `part` keeps each outside cell's inset from the cell's square:
// the exact test, over the cells near its bounds, stopping at the first too close.
bool KeepsInsets(const Polygon2d& part, const CellInset& inset_at, double max_inset_cells) {
  const Bounds b = BoundsOf(part);
  return ForOutsideCellsNear(b, inset_at, max_inset_cells, [&](const InsetCell& cell) { return !TooClose(part, b, cell); });
}

// KeepsInsets over `cells` (CellsNear of a box holding the part). The cell at *hint
// (an index into cells, when set) is tested first and a cell found too close is left
// there: the cell that failed a bisection step is the likeliest to fail the next (the
// answer does not depend on the order).
bool KeepsInsets(const Polygon2d& part, const std::vector<InsetCell>& cells, std::optional<size_t>* hint) {
  const Bounds b = BoundsOf(part);
  if (hint->has_value() && TooClose(part, b, cells[**hint])) return false;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (hint->has_value() && i == **hint) continue;
    if (!TooClose(part, b, cells[i])) continue;
    *hint = i;
    return false;
  }
  return true;
}

// The pieces other than `self` whose bounds meet `box` grown by a rounding margin: the
// only ones a part inside the box can meet (its bounds lie in the box).
std::vector<size_t> PiecesNear(const Bounds& box, const std::vector<Bounds>& bounds, size_t self) {
  constexpr double kMargin = 1e-6;  // [cells], far above a clip's rounding
  Bounds grown = box;
  grown.lo.array() -= kMargin;
  grown.hi.array() += kMargin;
  std::vector<size_t> near;
  for (size_t k = 0; k < bounds.size(); ++k) {
    if (k != self && bounds[k].Meets(grown)) near.push_back(k);
  }
  return near;
}

// Whether `part` overlaps no interior of the pieces `near` (PiecesNear of a box holding it).
bool ClearOfOthers(const Polygon2d& part, const std::vector<Polygon2d>& pieces, const std::vector<Bounds>& bounds,
                   const std::vector<size_t>& near) {
  const Bounds b = BoundsOf(part);
  for (const size_t k : near) {
    if (bounds[k].Meets(b) && !InteriorsApart(part, pieces[k])) return false;
  }
  return true;
}

}  // namespace

void AddSideSlack(std::vector<Polygon2d>* pieces, const CellInset& inset_at, double max_inset_cells,
                  const SideSlackOptions& options) {
  std::vector<Bounds> bounds;
  for (const Polygon2d& piece : *pieces) bounds.push_back(BoundsOf(piece));
  const double finest = options.most_cells / std::ldexp(1.0, std::max(0, options.bisections));
  Polygon2d before_side, moved_piece, part, scratch;  // work space of the tests
  for (size_t k = 0; k < pieces->size() && !options.deadline.Expired(); ++k) {
    Polygon2d& piece = (*pieces)[k];
    if (piece.size() < 3) continue;
    std::vector<HalfPlane> planes = HalfPlanesOf(piece);
    Bounds box = BoundsOf(piece);  // every side moves at most most_cells
    box.lo.array() -= options.most_cells;
    box.hi.array() += options.most_cells;
    bool moved_any = false;
    // Only this piece changes while its sides move: the others it may meet are found once.
    const std::vector<size_t> near = options.may_overlap ? std::vector<size_t>() : PiecesNear(box, bounds, k);
    for (size_t j = 0; j < planes.size(); ++j) {
      if (planes[j].normal.isZero()) continue;
      // What moving side j out by `shift` adds: the moved polygon beyond the side's line.
      // Every shift tried is at most most_cells, and what it adds lies in what that adds:
      // the cells near the latter's bounds (grown for rounding) are the only ones to test.
      // The box clipped by the sides before j, which no shift of side j changes: the
      // clips in Intersection's order, so the same polygons.
      before_side = {box.lo, {box.hi.x(), box.lo.y()}, box.hi, {box.lo.x(), box.hi.y()}};
      ClipBy(planes, 0, j, planes.size(), 0.0, &before_side, &scratch);
      auto added = [&](double shift) {
        moved_piece = before_side;
        ClipBy(planes, j, planes.size(), j, shift, &moved_piece, &scratch);
        KeepBelowLineInto(moved_piece, -planes[j].normal, -planes[j].offset, &part);
      };
      added(finest);
      if (part.size() >= 3 && !(KeepsInsets(part, inset_at, max_inset_cells) &&
                                (options.may_overlap || ClearOfOthers(part, *pieces, bounds, near)))) {
        continue;  // no room: skip the bisection
      }
      added(options.most_cells);
      constexpr double kMargin = 1e-6;  // [cells], far above a clip's rounding
      Bounds most = part.size() >= 3 ? BoundsOf(part) : moved_piece.size() >= 3 ? BoundsOf(moved_piece) : box;
      most.lo.array() -= kMargin;
      most.hi.array() += kMargin;
      const std::vector<InsetCell> cells = CellsNear(most, inset_at, max_inset_cells);
      std::optional<size_t> failed;  // the cell (in cells) that last failed a test of this side
      auto sound = [&](double shift) {
        added(shift);
        if (part.size() < 3) return true;
        return KeepsInsets(part, cells, &failed) && (options.may_overlap || ClearOfOthers(part, *pieces, bounds, near));
      };
      double lo = finest, hi = options.most_cells;
      for (int it = 1; it < options.bisections; ++it) {
        const double mid = 0.5 * (lo + hi);
        (sound(mid) ? lo : hi) = mid;
      }
      planes[j].offset += lo;
      moved_any = true;
      // Later sides are judged against the piece as moved so far.
      Intersection(planes, planes.size(), 0.0, box, &piece, &scratch);
      bounds[k] = BoundsOf(piece);
    }
    if (moved_any) piece = SimplifyConvex(std::move(piece), options.max_vertices);
    bounds[k] = BoundsOf(piece);
  }
}

}  // namespace mfp
