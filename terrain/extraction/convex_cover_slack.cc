#include <algorithm>
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

// The polygon's half-planes with edge `moved` pushed out by `shift`, within `box`, into
// `polygon` (`scratch`: the caller's work space).
void Intersection(const std::vector<HalfPlane>& planes, size_t moved, double shift, const Bounds& box, Polygon2d* polygon,
                  Polygon2d* scratch) {
  *polygon = {box.lo, {box.hi.x(), box.lo.y()}, box.hi, {box.lo.x(), box.hi.y()}};
  for (size_t j = 0; j < planes.size() && polygon->size() >= 3; ++j) {
    if (planes[j].normal.isZero()) continue;
    KeepBelowLineInto(*polygon, planes[j].normal, planes[j].offset + (j == moved ? shift : 0.0), scratch);
    std::swap(*polygon, *scratch);
  }
}

// Whether two convex polygons' interiors are apart: some edge of either separates them.
bool InteriorsApart(const Polygon2d& p, const Polygon2d& q) {
  for (const Polygon2d* a : {&p, &q}) {
    const Polygon2d* b = a == &p ? &q : &p;
    for (const HalfPlane& h : HalfPlanesOf(*a)) {
      if (h.normal.isZero()) continue;
      double lowest = INFINITY;
      for (const Eigen::Vector2d& v : *b) lowest = std::min(lowest, h.normal.dot(v) - h.offset);
      if (lowest >= -kEps) return true;
    }
  }
  return false;
}

// A cell, by row and column.
struct Cell {
  int r = 0, c = 0;
};

// Whether every point of `part` keeps each outside cell's inset from the cell's square
// (cell (r, c) spans [c - 0.5, c + 0.5] x [r - 0.5, r + 0.5]): the exact test. The cell at
// *hint (when set) is tested first and a cell found too close is left there: the cell that
// failed a bisection step is the likeliest to fail the next (the answer does not depend on
// the order, and a cell beyond the scanned box passes, so testing it changes nothing).
bool KeepsInsets(const Polygon2d& part, const CellInset& inset_at, double max_inset_cells, std::optional<Cell>* hint) {
  const Bounds b = BoundsOf(part);
  const double reach = max_inset_cells + 0.5;
  const int r0 = static_cast<int>(std::floor(b.lo.y() - reach)), r1 = static_cast<int>(std::ceil(b.hi.y() + reach));
  const int c0 = static_cast<int>(std::floor(b.lo.x() - reach)), c1 = static_cast<int>(std::ceil(b.hi.x() + reach));
  auto too_close = [&](int r, int c) {
    const double inset = inset_at(r, c);
    if (inset <= 0.0) return false;  // a patch cell, or no inset asked
    const double dy = std::max({0.0, (r - 0.5) - b.hi.y(), b.lo.y() - (r + 0.5)});
    const double dx = std::max({0.0, (c - 0.5) - b.hi.x(), b.lo.x() - (c + 0.5)});
    // The boxes are far enough apart. Squared with a relative margin of 1e-12, so a cell
    // skipped here is one the exact distance would pass as well.
    if (dx * dx + dy * dy >= inset * inset * (1.0 + 1e-12)) return false;
    const Polygon2d cell = {{c - 0.5, r - 0.5}, {c + 0.5, r - 0.5}, {c + 0.5, r + 0.5}, {c - 0.5, r + 0.5}};
    return ConvexPolygonDistance(part, cell) < inset - kEps;
  };
  const bool hinted = hint->has_value() && (*hint)->r >= r0 && (*hint)->r <= r1 && (*hint)->c >= c0 && (*hint)->c <= c1;
  if (hinted && too_close((*hint)->r, (*hint)->c)) return false;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (hinted && r == (*hint)->r && c == (*hint)->c) continue;
      if (!too_close(r, c)) continue;
      *hint = Cell{r, c};
      return false;
    }
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
  Polygon2d moved_piece, part, scratch;  // work space of the tests
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
      std::optional<Cell> failed;  // the cell that last failed a test of this side
      auto sound = [&](double shift) {
        Intersection(planes, j, shift, box, &moved_piece, &scratch);
        KeepBelowLineInto(moved_piece, -planes[j].normal, -planes[j].offset, &part);
        if (part.size() < 3) return true;
        return KeepsInsets(part, inset_at, max_inset_cells, &failed) &&
               (options.may_overlap || ClearOfOthers(part, *pieces, bounds, near));
      };
      if (!sound(finest)) continue;  // no room: skip the bisection
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
