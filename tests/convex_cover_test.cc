#include "terrain/extraction/internal/convex_cover.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include "terrain/extraction/internal/patch_cover.h"
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
      for (const bool shrunk_seeds : {true, false}) {
        ConvexCoverOptions o = Options(40, overlap);
        o.shrunk_seeds = shrunk_seeds;
        o.shrunk_seed_min_cells = 1 + trial % 4;
        const std::vector<Polygon2d> pieces = ConvexCoverOfSquares(s.cells, rows, cols, o);
        const Judged j = Judge(s, pieces);
        EXPECT_EQ(j.off_set, 0) << "trial " << trial << " overlap " << overlap << " shrunk seeds " << shrunk_seeds;
        EXPECT_EQ(j.not_convex, 0) << "trial " << trial;
        if (!overlap) {
          EXPECT_EQ(j.overlapping, 0) << "trial " << trial;
        }
        for (const Polygon2d& piece : pieces) EXPECT_LE(piece.size(), 8u);
      }
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
  for (const bool shrunk_seeds : {true, false}) {
    ConvexCoverOptions o = Options(30, false);
    o.shrunk_seeds = shrunk_seeds;
    const Judged j = Judge(s, ConvexCoverOfSquares(s.cells, s.rows, s.cols, o));
    const double rectangles = RectangleShare(s, o.cover);
    std::printf("floor with holes, 30 pieces, shrunk seeds %d: convex %.1f %%, rectangles %.1f %%\n", shrunk_seeds,
                100 * Fraction(j), 100 * rectangles);
    EXPECT_EQ(j.off_set, 0);
    EXPECT_EQ(j.overlapping, 0);
    EXPECT_GE(Fraction(j), rectangles);
  }
}

// shrunk_seed_min_cells gates the shrunk seeds by the seed's shorter side: at 1 every seed
// shrinks (the cover's default), above every seed's side none does (the seed alone), and
// the gate changes the cover of some of the random sets (else it would test nothing); a set
// of strips two squares high (so every seed is at most 2 thin) is covered at 3 as by the
// seeds alone.
TEST(ConvexCover, OnlySeedsAtLeastTheMinimumSideAreShrunk) {
  uint32_t state = 777;
  auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
  int gate_changed_cover = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const int rows = 10 + int(next() % 20), cols = 10 + int(next() % 20);
    const SquareSet s = MakeSet(rows, cols, [&](int, int) { return int(next() % 100) < 85; });
    ConvexCoverOptions o = Options(40, false);
    o.shrunk_seed_min_cells = 1;
    const std::vector<Polygon2d> all_shrunk = ConvexCoverOfSquares(s.cells, rows, cols, o);
    o.shrunk_seed_min_cells = rows + cols;  // wider than any seed
    const std::vector<Polygon2d> none_shrunk = ConvexCoverOfSquares(s.cells, rows, cols, o);
    if (none_shrunk != all_shrunk) ++gate_changed_cover;
    o.shrunk_seed_min_cells = 1;
    o.shrunk_seeds = false;
    EXPECT_EQ(ConvexCoverOfSquares(s.cells, rows, cols, o), none_shrunk) << "trial " << trial;
  }
  EXPECT_GT(gate_changed_cover, 0);
  // Strips two squares high: with a minimum side of 3 no seed shrinks.
  const SquareSet strips = MakeSet(30, 30, [](int r, int c) { return r % 3 != 2 && (c * 5 + r) % 11 != 0; });
  ConvexCoverOptions o = Options(60, false);
  o.shrunk_seeds = false;
  const std::vector<Polygon2d> unshrunk = ConvexCoverOfSquares(strips.cells, strips.rows, strips.cols, o);
  o.shrunk_seeds = true;
  o.shrunk_seed_min_cells = 3;
  EXPECT_EQ(ConvexCoverOfSquares(strips.cells, strips.rows, strips.cols, o), unshrunk);
  const Judged j = Judge(strips, unshrunk);
  EXPECT_EQ(j.off_set, 0);
  EXPECT_EQ(j.overlapping, 0);
}

TEST(ConvexCover, PolygonMeetsSquareOnlyWithArea) {
  const Polygon2d triangle = {{0, 0}, {2, 0}, {0, 2}};
  EXPECT_TRUE(PolygonMeetsSquare(triangle, 0, 0));
  EXPECT_FALSE(PolygonMeetsSquare(triangle, 1, 1));  // touches its corner (1, 1) only
  EXPECT_FALSE(PolygonMeetsSquare(triangle, 0, 2));  // beside it
  EXPECT_TRUE(PolygonMeetsSquare(triangle, 0, 1));
}

// A surface of cells (cell (r, c) spans [c - 0.5, c + 0.5] x [r - 0.5, r + 0.5]) whose
// outside cells each ask an inset [cells]: the kept cells (centre at least each outside
// cell's inset from its square) and their complete dual squares, computed by brute force.
struct Surface {
  SquareSet cells;                // the surface's cells
  std::vector<double> inset;      // per cell of the box, the inset it asks when outside
  double max_inset = 0.0;
  double InsetAt(int r, int c) const {
    if (cells.In(r, c)) return -1.0;
    if (r < 0 || r >= cells.rows || c < 0 || c >= cells.cols) return max_inset;
    return inset[size_t(r) * cells.cols + c];
  }
};

double PointSquareDistance(const Eigen::Vector2d& p, int r, int c) {
  const double dx = std::max({0.0, (c - 0.5) - p.x(), p.x() - (c + 0.5)});
  const double dy = std::max({0.0, (r - 0.5) - p.y(), p.y() - (r + 0.5)});
  return std::hypot(dx, dy);
}

// The smallest margin (distance to an outside cell's square minus its inset) of a point.
double WorstMargin(const Surface& s, const Eigen::Vector2d& p) {
  const int reach = int(std::ceil(s.max_inset)) + 2;
  double worst = INFINITY;
  for (int r = int(std::floor(p.y())) - reach; r <= int(std::ceil(p.y())) + reach; ++r) {
    for (int c = int(std::floor(p.x())) - reach; c <= int(std::ceil(p.x())) + reach; ++c) {
      const double inset = s.InsetAt(r, c);
      if (inset > 0.0) worst = std::min(worst, PointSquareDistance(p, r, c) - inset);
    }
  }
  return worst;
}

SquareSet DualSquaresOf(const Surface& s) {
  const int rows = s.cells.rows, cols = s.cells.cols;
  const SquareSet kept = MakeSet(rows, cols, [&](int r, int c) {
    return s.cells.In(r, c) && WorstMargin(s, Eigen::Vector2d(c, r)) >= 0.0;
  });
  return MakeSet(rows - 1, cols - 1, [&](int r, int c) {
    return kept.In(r, c) && kept.In(r + 1, c) && kept.In(r, c + 1) && kept.In(r + 1, c + 1);
  });
}

double Area(const Polygon2d& polygon) {
  double twice = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) twice += Cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * twice;
}

struct SlackJudged {
  long samples = 0, unsafe = 0, overlapping = 0;
  int not_convex = 0;
};

// Samples every piece (offsets off the lattice) and checks each sample's margin.
SlackJudged JudgeSlack(const Surface& s, const std::vector<Polygon2d>& pieces) {
  SlackJudged j;
  for (const Polygon2d& piece : pieces) {
    for (size_t i = 0; i < piece.size(); ++i) {
      const Eigen::Vector2d& a = piece[i];
      if (Cross(piece[(i + 1) % piece.size()] - a, piece[(i + 2) % piece.size()] - a) < -1e-9) ++j.not_convex;
    }
    Eigen::Vector2d lo = piece.front(), hi = piece.front();
    for (const Eigen::Vector2d& p : piece) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    for (double y = lo.y() + 0.0037; y <= hi.y(); y += 0.07) {
      for (double x = lo.x() + 0.0051; x <= hi.x(); x += 0.07) {
        const Eigen::Vector2d p(x, y);
        if (!InsideBy(piece, p, 0.0)) continue;
        ++j.samples;
        if (WorstMargin(s, p) < -1e-7) ++j.unsafe;
      }
    }
    // The piece's vertices too: the farthest points a side moved to.
    for (const Eigen::Vector2d& v : piece) j.unsafe += WorstMargin(s, v) < -1e-7 ? 1 : 0;
  }
  // Overlap: samples well inside two pieces.
  for (double y = -1.0137; y < s.cells.rows + 1; y += 0.05) {
    for (double x = -1.0093; x < s.cells.cols + 1; x += 0.05) {
      int well_inside = 0;
      for (const Polygon2d& piece : pieces) well_inside += InsideBy(piece, Eigen::Vector2d(x, y), 1e-6) ? 1 : 0;
      if (well_inside > 1) ++j.overlapping;
    }
  }
  return j;
}

// Random surfaces with holes and ragged outlines, each outside cell asking its own inset
// (0.6 - 2.4 cells): every point of every piece with side slack keeps every inset, the
// pieces stay convex, meet in no area, and the slack adds area.
TEST(ConvexCoverSlack, PiecesWithSideSlackKeepEveryOutsideCellsInset) {
  uint32_t state = 777;
  auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
  for (int trial = 0; trial < 10; ++trial) {
    Surface s;
    const int rows = 14 + int(next() % 16), cols = 14 + int(next() % 16);
    const int holes = 1 + int(next() % 4);  // per cent of cells off the surface
    s.cells = MakeSet(rows, cols, [&](int r, int c) {
      const bool edge = r == 0 || c == 0 || r == rows - 1 || c == cols - 1;
      return !edge && int(next() % 100) >= holes;
    });
    s.inset.resize(size_t(rows) * cols);
    for (double& v : s.inset) v = 0.6 + 0.01 * double(next() % 181);
    s.max_inset = 2.4;
    const SquareSet dual = DualSquaresOf(s);
    std::vector<Polygon2d> pieces = ConvexCoverOfSquares(dual.cells, dual.rows, dual.cols, Options(30, false));
    double before = 0.0, after = 0.0;
    for (const Polygon2d& p : pieces) before += Area(p);
    SideSlackOptions slack;
    AddSideSlack(&pieces, [&](int r, int c) { return s.InsetAt(r, c); }, s.max_inset, slack);
    for (const Polygon2d& p : pieces) after += Area(p);
    const SlackJudged j = JudgeSlack(s, pieces);
    EXPECT_GT(j.samples, 0) << "trial " << trial;
    EXPECT_EQ(j.unsafe, 0) << "trial " << trial;
    EXPECT_EQ(j.not_convex, 0) << "trial " << trial;
    EXPECT_EQ(j.overlapping, 0) << "trial " << trial;
    for (const Polygon2d& piece : pieces) EXPECT_LE(piece.size(), 8u);
    if (!pieces.empty()) {
      EXPECT_GT(after, before) << "trial " << trial;
    }
  }
}

// One square pit in a floor, inset 1.3 cells: the dual squares stop at the kept cells'
// centres, 0.2 cells short of the exact inset from the border and up to a cell short
// around the pit; with slack the sides reach the exact inset.
TEST(ConvexCoverSlack, SidesReachTheExactInsetAroundAPit) {
  Surface s;
  const int n = 24;
  s.cells = MakeSet(n, n, [&](int r, int c) { return r > 0 && c > 0 && r < n - 1 && c < n - 1 && !(r == 11 && c == 12); });
  s.inset.assign(size_t(n) * n, 1.3);
  s.max_inset = 1.3;
  const SquareSet dual = DualSquaresOf(s);
  std::vector<Polygon2d> pieces = ConvexCoverOfSquares(dual.cells, dual.rows, dual.cols, Options(16, false));
  double before = 0.0, after = 0.0;
  for (const Polygon2d& p : pieces) before += Area(p);
  AddSideSlack(&pieces, [&](int r, int c) { return s.InsetAt(r, c); }, s.max_inset, SideSlackOptions());
  for (const Polygon2d& p : pieces) after += Area(p);
  // The floor's cells span [0.5, n - 1.5] on each axis; inset 1.3 from the border cells
  // leaves [1.8, n - 2.8]; the pit's square grown by 1.3 (rounded corners) takes 11.5.
  const double exact = (n - 4.6) * (n - 4.6) - 11.5;
  std::printf("pit: %zu pieces, area %.2f without slack, %.2f with, exact inset floor %.2f\n", pieces.size(), before,
              after, exact);
  EXPECT_EQ(JudgeSlack(s, pieces).unsafe, 0);
  EXPECT_LE(after, exact + 1e-6);
  EXPECT_GT(after, before + 0.2 * 4 * (n - 6.0));  // 0.2 cells along the border at least
}

// A deadline that has passed ends both covers before their first piece: what they return
// (nothing) is sound; the slack leaves the pieces as they are.
TEST(ConvexCoverSlack, AnExpiredDeadlineEndsTheCoversAndTheSlack) {
  const SquareSet s = MakeSet(20, 20, [](int r, int c) { return (r * 7 + c * 13) % 37 != 0; });
  ConvexCoverOptions o = Options(30, false);
  EXPECT_FALSE(ConvexCoverOfSquares(s.cells, s.rows, s.cols, o).empty());
  EXPECT_FALSE(GreedyRectangleCover(s.cells, s.rows, s.cols, o.cover).empty());
  o.cover.deadline = Deadline::After(0.0);
  EXPECT_TRUE(ConvexCoverOfSquares(s.cells, s.rows, s.cols, o).empty());
  EXPECT_TRUE(GreedyRectangleCover(s.cells, s.rows, s.cols, o.cover).empty());
  std::vector<Polygon2d> pieces = {{{2, 2}, {5, 2}, {5, 5}, {2, 5}}};
  SideSlackOptions slack;
  slack.deadline = Deadline::After(0.0);
  AddSideSlack(&pieces, [](int, int) { return 1.0; }, 1.0, slack);
  EXPECT_EQ(pieces.front(), (Polygon2d{{2, 2}, {5, 2}, {5, 5}, {2, 5}}));
}

}  // namespace
}  // namespace mfp
