#include "terrain/extraction/internal/convex_cover.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "base/check.h"
#include "geometry/free_region_2d.h"
#include "terrain/extraction/internal/uncovered_rectangles.h"

namespace mfp {
namespace {

constexpr double kEps = 1e-9;  // rounding allowance in square units

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

Polygon2d RectPolygon(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// Whether a point lies in a counter-clockwise polygon (up to kEps times an edge's length,
// at least one), each edge's vector and allowance computed once for the many points asked.
class PolygonContains {
 public:
  explicit PolygonContains(const Polygon2d& polygon) {
    edges_.reserve(polygon.size());
    for (size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& a = polygon[i];
      const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - a;
      edges_.push_back({a, e, -kEps * std::max(1.0, e.norm())});
    }
  }
  bool operator()(const Eigen::Vector2d& p) const {
    for (const Edge& edge : edges_) {
      if (Cross(edge.vector, p - edge.start) < edge.allowance) return false;
    }
    return true;
  }

 private:
  struct Edge {
    Eigen::Vector2d start, vector;
    double allowance;
  };
  std::vector<Edge> edges_;
};

struct Box {
  double x0, y0, x1, y1;
  bool Meets(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

Box BoundingBox(const Polygon2d& polygon) {
  Box box{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (const Eigen::Vector2d& p : polygon) {
    box.x0 = std::min(box.x0, p.x());
    box.y0 = std::min(box.y0, p.y());
    box.x1 = std::max(box.x1, p.x());
    box.y1 = std::max(box.y1, p.y());
  }
  return box;
}

// The cover so far over the lattice.
class CoverState {
 public:
  CoverState(const std::vector<uint8_t>& squares, int rows, int cols, const ConvexCoverOptions& options)
      : squares_(squares), rows_(rows), cols_(cols), options_(options), open_(squares, rows, cols),
        owner_(squares.size(), -1) {
    for (uint8_t s : squares) total_ += s ? 1 : 0;
    row_obstacles_.assign(static_cast<size_t>(rows) + 1, 0);
    // A square touches the set when a square of the set lies in its 3 x 3 block: the set
    // ORed over three rows, then over three columns.
    std::vector<uint8_t> rows_near(static_cast<size_t>(cols));
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        rows_near[static_cast<size_t>(c)] = InSet(r - 1, c) || InSet(r, c) || InSet(r + 1, c);
      }
      for (int c = 0; c < cols; ++c) {
        const bool touches = rows_near[static_cast<size_t>(c)] || (c > 0 && rows_near[static_cast<size_t>(c) - 1]) ||
                             (c + 1 < cols && rows_near[static_cast<size_t>(c) + 1]);
        if (!squares[Index(r, c)] && touches) obstacle_cols_.push_back(c);
      }
      row_obstacles_[static_cast<size_t>(r) + 1] = obstacle_cols_.size();
    }
  }

  size_t total() const { return total_; }
  size_t covered() const { return covered_; }
  const std::vector<uint8_t>& open() const { return open_.cells(); }
  // The largest rectangle of open squares (LargestRectangle of open(), kept up to date).
  CellRect LargestOpen() const { return open_.Largest(); }
  const std::vector<int>& owner() const { return owner_; }
  const std::vector<Polygon2d>& pieces() const { return pieces_; }

  // Grows pieces about the seed rectangle and (shrunk_seeds, on a seed at least
  // shrunk_seed_min_cells on its shorter side) about its middle half and quarter (a seed
  // flush with the set's outline on a side keeps that side straight; a smaller one lets
  // the cuts turn toward the obstacles around it), adds the one that holds the most new
  // squares; false when none holds a new square.
  bool AddPiece(const CellRect& seed) {
    Polygon2d best, last_seed;
    size_t best_new = 0;
    const bool shrink = options_.shrunk_seeds && std::min(seed.rows, seed.cols) >= options_.shrunk_seed_min_cells;
    for (const double keep : {1.0, 0.5, 0.25}) {
      if (keep < 1.0 && !shrink) break;
      // A later seed wins only by holding more: none can once every square left is held,
      // and a seed the same as the last grows the same piece.
      if (best_new > 0 && best_new == total_ - covered_) break;
      Polygon2d shrunk = Shrunk(seed, keep);
      if (shrunk == last_seed) continue;
      const Polygon2d piece = Grow(shrunk);
      last_seed = std::move(shrunk);
      const size_t newly = Mark(piece, /*dry_run=*/true);
      if (newly > best_new) {
        best_new = newly;
        best = piece;
      }
    }
    if (best_new == 0) {
      best = RectPolygon(seed.col0, seed.row0, seed.col0 + seed.cols, seed.row0 + seed.rows);
      if (Mark(best, /*dry_run=*/true) == 0) return false;
    }
    covered_ += Mark(best, /*dry_run=*/false);
    boxes_.push_back(BoundingBox(best));
    pieces_.push_back(std::move(best));
    return true;
  }

 private:
  size_t Index(int r, int c) const { return static_cast<size_t>(r) * cols_ + c; }
  bool InSet(int r, int c) const { return r >= 0 && r < rows_ && c >= 0 && c < cols_ && squares_[Index(r, c)]; }

  static constexpr int kNearCells = 8;  // Grow's first window beyond the seed [cells]

  // The seed's middle `keep` share of each side (at least one square).
  static Polygon2d Shrunk(const CellRect& seed, double keep) {
    const double w = std::max(1.0, keep * seed.cols), h = std::max(1.0, keep * seed.rows);
    const double x0 = seed.col0 + std::floor(0.5 * (seed.cols - w)), y0 = seed.row0 + std::floor(0.5 * (seed.rows - h));
    return RectPolygon(x0, y0, x0 + std::round(w), y0 + std::round(h));
  }

  // The convex region about the seed among the obstacle squares (and the earlier pieces
  // when pieces may not overlap) within the seed's reach, its vertices thinned.
  Polygon2d Grow(const Polygon2d& seed_polygon) const {
    const Box seed = BoundingBox(seed_polygon);
    const int reach = std::max({options_.reach_cells, int(seed.x1 - seed.x0), int(seed.y1 - seed.y0)});
    const Window window{std::max(0, int(seed.x0) - reach), std::max(0, int(seed.y0) - reach),
                        std::min(cols_, int(seed.x1) + reach), std::min(rows_, int(seed.y1) + reach)};
    // First among the obstacle squares within kNearCells of the seed only: a square farther
    // out has a gap of at least kNearCells along one of the seed's sides, so it would not
    // have changed the region when the region, as it was when the gaps reached kNearCells,
    // lies strictly inside the near window (checked; else grown again among all).
    const Window near{std::max(window.c0, int(seed.x0) - kNearCells), std::max(window.r0, int(seed.y0) - kNearCells),
                      std::min(window.c1, int(seed.x1) + kNearCells), std::min(window.r1, int(seed.y1) + kNearCells)};
    Eigen::Vector2d near_lo, near_hi;
    const size_t near_count = Obstacles(near, window);  // before obstacles_.data(): it may grow the vector
    std::optional<FreeRegion2d> region = GrowFreeRegionNear(seed_polygon, obstacles_.data(), near_count, window.Lo(),
                                                            window.Hi(), kNearCells, &near_lo, &near_hi);
    constexpr double kMargin = 1e-9;  // for rounding in the region's later bounds [cells]
    const bool near_enough = (near.c0 == window.c0 || near_lo.x() > near.c0 + kMargin) &&
                             (near.r0 == window.r0 || near_lo.y() > near.r0 + kMargin) &&
                             (near.c1 == window.c1 || near_hi.x() < near.c1 - kMargin) &&
                             (near.r1 == window.r1 || near_hi.y() < near.r1 - kMargin);
    if (region && !near_enough) {
      const size_t count = Obstacles(window, window);
      region = GrowFreeRegionNear(seed_polygon, obstacles_.data(), count, window.Lo(), window.Hi(),
                                  std::numeric_limits<double>::infinity(), &near_lo, &near_hi);
    }
    if (!region || region->polygon.size() < 3) return seed_polygon;
    return SimplifyConvex(region->polygon, std::max(3, options_.max_vertices));
  }

  // Columns [c0, c1) x rows [r0, r1) of the lattice.
  struct Window {
    int c0, r0, c1, r1;
    Eigen::Vector2d Lo() const { return Eigen::Vector2d(c0, r0); }
    Eigen::Vector2d Hi() const { return Eigen::Vector2d(c1, r1); }
  };

  // The obstacle squares in `squares` row by row, then (without overlap) the earlier pieces
  // meeting `window`, into the first of obstacles_ (filled in place: no allocation once
  // the polygons have room); returns how many.
  size_t Obstacles(const Window& squares, const Window& window) const {
    size_t used = 0;
    auto add = [&](const Eigen::Vector2d* begin, const Eigen::Vector2d* end) {
      if (used == obstacles_.size()) obstacles_.emplace_back();
      obstacles_[used++].assign(begin, end);
    };
    for (int r = squares.r0; r < squares.r1; ++r) {  // the obstacle squares of each row in [c0, c1), in order
      const auto row_end = obstacle_cols_.begin() + static_cast<std::ptrdiff_t>(row_obstacles_[static_cast<size_t>(r) + 1]);
      auto it = std::lower_bound(obstacle_cols_.begin() + static_cast<std::ptrdiff_t>(row_obstacles_[static_cast<size_t>(r)]),
                                 row_end, squares.c0);
      for (; it != row_end && *it < squares.c1; ++it) {
        const int c = *it;
        const Eigen::Vector2d square[4] = {{c, r}, {c + 1, r}, {c + 1, r + 1}, {c, r + 1}};
        add(square, square + 4);
      }
    }
    if (!options_.cover.grow_over_covered) {
      const Box box{double(window.c0), double(window.r0), double(window.c1), double(window.r1)};
      for (size_t k = 0; k < pieces_.size(); ++k) {
        if (boxes_[k].Meets(box)) add(pieces_[k].data(), pieces_[k].data() + pieces_[k].size());
      }
    }
    return used;
  }

  // Squares the piece holds wholly become owned; without overlap, squares it meets close
  // for seeds. Returns the squares newly held (dry_run: counts, changes nothing).
  size_t Mark(const Polygon2d& piece, bool dry_run) {
    const Box box = BoundingBox(piece);
    const int c0 = std::max(0, static_cast<int>(std::floor(box.x0))), c1 = std::min(cols_, static_cast<int>(std::ceil(box.x1)));
    const int r0 = std::max(0, static_cast<int>(std::floor(box.y0))), r1 = std::min(rows_, static_cast<int>(std::ceil(box.y1)));
    size_t newly = 0;
    closing_.clear();
    // Whether the piece holds each lattice point of the box (a square's four corners).
    const int width = c1 - c0 + 1;
    corner_in_.resize(static_cast<size_t>(std::max(0, r1 - r0 + 1) * std::max(0, width)));  // every one set below
    const PolygonContains contains(piece);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) corner_in_[static_cast<size_t>((r - r0) * width + (c - c0))] = contains({c, r});
    }
    for (int r = r0; r < r1; ++r) {
      const uint8_t* below = &corner_in_[static_cast<size_t>((r - r0) * width)];
      const uint8_t* above = below + width;
      for (int c = c0; c < c1; ++c) {
        const size_t i = Index(r, c);
        if (!squares_[i] || (dry_run && owner_[i] >= 0)) continue;
        const int k = c - c0;
        const bool whole = below[k] && below[k + 1] && above[k + 1] && above[k];
        if (whole && owner_[i] < 0) ++newly;
        if (dry_run) continue;
        if (whole) {
          if (owner_[i] < 0) owner_[i] = static_cast<int>(pieces_.size());
          closing_.push_back(i);
        } else if (!options_.cover.grow_over_covered && PolygonMeetsSquare(piece, r, c)) {
          closing_.push_back(i);
        }
      }
    }
    if (!dry_run) open_.ClearCells(closing_);
    return newly;
  }

  const std::vector<uint8_t>& squares_;
  int rows_, cols_;
  const ConvexCoverOptions& options_;
  UncoveredRectangles open_;  // squares a seed may use
  std::vector<size_t> closing_;  // Mark's work space: the squares it closes
  std::vector<uint8_t> corner_in_;  // Mark's work space: the lattice points the piece holds
  mutable std::vector<Polygon2d> obstacles_;  // Grow's work space: the first Obstacles() ones used
  std::vector<int> owner_;     // a piece holding the square wholly, -1 when none does
  std::vector<int> obstacle_cols_;       // the obstacle squares' (outside the set, touching it) columns, row by row
  std::vector<size_t> row_obstacles_;  // row r's are obstacle_cols_[row_obstacles_[r], row_obstacles_[r + 1])
  std::vector<Polygon2d> pieces_;
  std::vector<Box> boxes_;
  size_t total_ = 0, covered_ = 0;
};

}  // namespace

// Drops vertices that add (almost) no area, then, while more than max_vertices remain, the
// vertex whose triangle with its neighbours is smallest: the hull of the rest lies inside.
Polygon2d SimplifyConvex(Polygon2d polygon, int max_vertices) {
  auto triangle = [&](size_t i) {
    const size_t n = polygon.size();
    const Eigen::Vector2d& prev = polygon[(i + n - 1) % n];
    return std::abs(Cross(polygon[i] - prev, polygon[(i + 1) % n] - prev));
  };
  while (polygon.size() > 3) {
    size_t smallest = 0;
    for (size_t i = 1; i < polygon.size(); ++i) {
      if (triangle(i) < triangle(smallest)) smallest = i;
    }
    if (static_cast<int>(polygon.size()) <= max_vertices && triangle(smallest) > 1e-9) break;
    polygon.erase(polygon.begin() + static_cast<long>(smallest));
  }
  return polygon;
}

bool PolygonMeetsSquare(const Polygon2d& polygon, int r, int c) {
  const Box box = BoundingBox(polygon);
  if (box.x1 <= c + kEps || box.x0 >= c + 1 - kEps || box.y1 <= r + kEps || box.y0 >= r + 1 - kEps) return false;
  const Polygon2d square = RectPolygon(c, r, c + 1, r + 1);
  for (size_t i = 0; i < polygon.size(); ++i) {  // a polygon edge's line separating the square
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - polygon[i];
    const double length = e.norm();
    if (length < 1e-12) continue;
    const Eigen::Vector2d n(e.y() / length, -e.x() / length);  // outward
    double lowest = INFINITY;
    for (const Eigen::Vector2d& q : square) lowest = std::min(lowest, n.dot(q - polygon[i]));
    if (lowest >= -kEps) return false;
  }
  return true;
}

std::vector<Polygon2d> ConvexCoverOfSquares(const std::vector<uint8_t>& squares, int rows, int cols,
                                            const ConvexCoverOptions& options) {
  MFP_CHECK(squares.size() == static_cast<size_t>(rows) * static_cast<size_t>(cols));
  CoverState state(squares, rows, cols, options);
  const RectangleCoverOptions& cover = options.cover;
  const int min_seed = std::max(1, cover.min_rect_cells);
  auto room = [&] { return static_cast<int>(state.pieces().size()) < cover.max_rects && !cover.deadline.Expired(); };
  while (room() && state.covered() < state.total() &&
         static_cast<double>(state.covered()) < cover.target_coverage * static_cast<double>(state.total())) {
    const CellRect seed = state.LargestOpen();
    if (seed.Area() < min_seed || !state.AddPiece(seed)) break;
  }
  // As the rectangle cover: the part left may hold the only way between two pieces.
  while (cover.connect_pieces && room() && state.covered() < state.total()) {
    CellRect bounds;
    std::vector<uint8_t> bridge = UncoveredBridge(state.open(), state.owner(), rows, cols, &bounds);
    if (bridge.empty()) break;
    const CellRect seed = LargestRectangleWithin(bridge, rows, cols, bounds);
    if (seed.Area() < min_seed || !state.AddPiece(seed)) break;
  }
  return state.pieces();
}

}  // namespace mfp
