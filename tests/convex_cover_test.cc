#include "terrain/extraction/internal/convex_cover.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include "terrain/extraction/internal/rectangle_cover.h"

namespace mfp {
namespace {

struct SquareSet {
  int rows = 0, cols = 0;
  std::vector<uint8_t> cells;
  bool In(int r, int c) const { return r >= 0 && r < rows && c >= 0 && c < cols && cells[size_t(r) * cols + c]; }
};

SquareSet MakeSet(int rows, int cols, const std::function<bool(int, int)>& in) {
  SquareSet s{rows, cols, std::vector<uint8_t>(size_t(rows) * cols, 0)};
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) s.cells[size_t(r) * cols + c] = in(r, c) ? 1 : 0;
  }
  return s;
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Inside by at least `margin` from every edge (counter-clockwise polygon).
bool InsideBy(const Polygon2d& polygon, const Eigen::Vector2d& p, double margin) {
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - polygon[i];
    if (Cross(e, p - polygon[i]) / e.norm() < margin) return false;
  }
  return true;
}

// Sample points off the lattice lines (offsets no multiple of the step hits an integer).
template <typename Visit>
void ForSamples(const SquareSet& s, double step, Visit visit) {
  for (double y = 0.0137; y < s.rows; y += step) {
    for (double x = 0.0093; x < s.cols; x += step) visit(Eigen::Vector2d(x, y));
  }
}

struct Judged {
  long off_set = 0;      // samples inside a piece on a square outside the set
  long in_set = 0;       // samples on the set's squares
  long covered = 0;      // of them, inside a piece
  long overlapping = 0;  // samples well inside two pieces
  int not_convex = 0;    // pieces with a clockwise turn
};

Judged Judge(const SquareSet& s, const std::vector<Polygon2d>& pieces) {
  Judged j;
  for (const Polygon2d& piece : pieces) {
    for (size_t i = 0; i < piece.size(); ++i) {
      const Eigen::Vector2d& a = piece[i];
      if (Cross(piece[(i + 1) % piece.size()] - a, piece[(i + 2) % piece.size()] - a) < -1e-9) ++j.not_convex;
    }
  }
  ForSamples(s, 0.1, [&](const Eigen::Vector2d& p) {
    const bool in = s.In(int(std::floor(p.y())), int(std::floor(p.x())));
    int inside = 0, well_inside = 0;
    for (const Polygon2d& piece : pieces) {
      inside += InsideBy(piece, p, 0.0) ? 1 : 0;
      well_inside += InsideBy(piece, p, 1e-6) ? 1 : 0;
    }
    if (inside > 0 && !in) ++j.off_set;
    if (in) ++j.in_set;
    if (in && inside > 0) ++j.covered;
    if (well_inside > 1) ++j.overlapping;
  });
  return j;
}

double Fraction(const Judged& j) { return j.in_set > 0 ? double(j.covered) / j.in_set : 0.0; }

// The rectangle cover's share, judged the same way.
double RectangleShare(const SquareSet& s, const RectangleCoverOptions& options) {
  std::vector<Polygon2d> rects;
  for (const CellRect& r : GreedyRectangleCover(s.cells, s.rows, s.cols, options)) {
    rects.push_back({{r.col0, r.row0}, {r.col0 + r.cols, r.row0}, {r.col0 + r.cols, r.row0 + r.rows}, {r.col0, r.row0 + r.rows}});
  }
  return Fraction(Judge(s, rects));
}

ConvexCoverOptions Options(int max_pieces, bool overlap) {
  ConvexCoverOptions o;
  o.cover.max_rects = max_pieces;
  o.cover.target_coverage = 1.0;
  o.cover.grow_over_covered = overlap;
  return o;
}

TEST(ConvexCover, PiecesOfRandomSetsLieOnTheSetAndAreConvex) {
  uint32_t state = 12345;
  auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
  for (int trial = 0; trial < 12; ++trial) {
    const int rows = 8 + int(next() % 24), cols = 8 + int(next() % 24);
    const int density = 60 + int(next() % 35);  // per cent of squares in the set
    const SquareSet s = MakeSet(rows, cols, [&](int, int) { return int(next() % 100) < density; });
    for (const bool overlap : {true, false}) {
      const std::vector<Polygon2d> pieces = ConvexCoverOfSquares(s.cells, rows, cols, Options(40, overlap));
      const Judged j = Judge(s, pieces);
      EXPECT_EQ(j.off_set, 0) << "trial " << trial << " overlap " << overlap;
      EXPECT_EQ(j.not_convex, 0) << "trial " << trial;
      if (!overlap) {
        EXPECT_EQ(j.overlapping, 0) << "trial " << trial;
      }
      for (const Polygon2d& piece : pieces) EXPECT_LE(piece.size(), 8u);
    }
  }
}

TEST(ConvexCover, AnLShapeIsCoveredWhole) {
  const SquareSet s = MakeSet(20, 20, [](int r, int c) { return r < 6 || c < 6; });
  const std::vector<Polygon2d> pieces = ConvexCoverOfSquares(s.cells, s.rows, s.cols, Options(8, false));
  const Judged j = Judge(s, pieces);
  EXPECT_EQ(j.off_set, 0);
  EXPECT_EQ(j.covered, j.in_set);
  EXPECT_LE(pieces.size(), 3u);
}

// A ring of squares (radii 14 and 22 squares): with the same number of pieces, convex
// pieces along its chords cover more of it than rectangles, and never leave it.
TEST(ConvexCover, ARingIsCoveredByChordsBetterThanByRectangles) {
  const SquareSet s = MakeSet(46, 46, [](int r, int c) {
    const double d = std::hypot(r + 0.5 - 23.0, c + 0.5 - 23.0);
    return d >= 14.0 && d <= 22.0;
  });
  for (const int n : {12, 24}) {
    ConvexCoverOptions o = Options(n, true);
    const Judged j = Judge(s, ConvexCoverOfSquares(s.cells, s.rows, s.cols, o));
    const double rectangles = RectangleShare(s, o.cover);
    std::printf("ring, %d pieces: convex %.1f %%, rectangles %.1f %%\n", n, 100 * Fraction(j), 100 * rectangles);
    EXPECT_EQ(j.off_set, 0);
    EXPECT_GT(Fraction(j), rectangles + 0.03) << n << " pieces";
  }
}

// A floor with scattered single-square holes: the pieces pass between them on diagonals.
TEST(ConvexCover, AFloorWithHolesIsCoveredAtLeastAsWellAsByRectangles) {
  const SquareSet s = MakeSet(40, 40, [](int r, int c) { return (r * 7 + c * 13) % 37 != 0; });
  ConvexCoverOptions o = Options(30, false);
  const Judged j = Judge(s, ConvexCoverOfSquares(s.cells, s.rows, s.cols, o));
  const double rectangles = RectangleShare(s, o.cover);
  std::printf("floor with holes, 30 pieces: convex %.1f %%, rectangles %.1f %%\n", 100 * Fraction(j), 100 * rectangles);
  EXPECT_EQ(j.off_set, 0);
  EXPECT_EQ(j.overlapping, 0);
  EXPECT_GE(Fraction(j), rectangles);
}

TEST(ConvexCover, PolygonMeetsSquareOnlyWithArea) {
  const Polygon2d triangle = {{0, 0}, {2, 0}, {0, 2}};
  EXPECT_TRUE(PolygonMeetsSquare(triangle, 0, 0));
  EXPECT_FALSE(PolygonMeetsSquare(triangle, 1, 1));  // touches its corner (1, 1) only
  EXPECT_FALSE(PolygonMeetsSquare(triangle, 0, 2));  // beside it
  EXPECT_TRUE(PolygonMeetsSquare(triangle, 0, 1));
}

}  // namespace
}  // namespace mfp
