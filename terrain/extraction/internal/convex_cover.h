#pragma once
// Cover of a set of unit lattice squares by convex polygons lying wholly in the set's
// union: from a seed (the largest rectangle of squares not yet covered), a convex region
// is grown among the squares outside the set by half-plane cuts (GrowFreeRegion, the
// IRIS manner), so a piece follows the set's outline - diagonals between holes, the
// chords of a ring - where a rectangle stops at the first square outside in its row or
// column. Private to the extraction library.
//
// Soundness: a piece avoids the interior of every square outside the set that touches a
// square of the set (corner or side) and stays in the lattice box. A convex piece with
// area that reached into any other square outside the set would have to pass through one
// of those first (its interior is connected and starts in the set), so the piece lies in
// the closed union of the set's squares.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "base/deadline.h"
#include "terrain/extraction/internal/rectangle_cover.h"

namespace mfp {

// A convex polygon, counter-clockwise.
using Polygon2d = std::vector<Eigen::Vector2d>;

struct ConvexCoverOptions {
  RectangleCoverOptions cover;  // coverage target, the smallest seed, the most pieces, overlap, necks
  int max_vertices = 8;         // a piece keeps at most this many vertices (dropping one shrinks it)
  int reach_cells = 24;         // a piece reaches at most this far (and its seed's size) beyond its seed
  // Each piece is also grown about the seed's middle half and quarter (the cuts may then
  // turn toward the obstacles around it), the one holding the most new squares kept;
  // false: about the seed rectangle alone (a third of the growing).
  bool shrunk_seeds = true;
  // ... and only a seed at least this many squares on its shorter side: a thinner one
  // shrinks along its length alone, and its middle part grows nearly the same piece.
  int shrunk_seed_min_cells = 1;
};

// squares: row-major rows x cols, non-zero = in the set; square (r, c) spans
// [c, c + 1] x [r, r + 1]. Pieces in those units. With cover.grow_over_covered false the
// pieces meet in no area (each later piece is grown with the earlier ones as obstacles).
std::vector<Polygon2d> ConvexCoverOfSquares(const std::vector<uint8_t>& squares, int rows, int cols,
                                            const ConvexCoverOptions& options);

// The area of a convex polygon's part inside square (r, c) is positive (more than rounding).
bool PolygonMeetsSquare(const Polygon2d& polygon, int r, int c);

// The convex polygon with at most max_vertices vertices left by dropping, one at a time,
// the vertex whose triangle with its neighbours is smallest (and every vertex adding no
// area): it lies inside the given one.
Polygon2d SimplifyConvex(Polygon2d polygon, int max_vertices);

// Side slack: the pieces end at the dual squares, while a foot centre is safe up to each
// outside cell's exact inset. inset_at(r, c): the inset [cells] cell (r, c) asks, its
// square spanning [c - 0.5, c + 0.5] x [r - 0.5, r + 0.5] (the dual squares' frame);
// zero or negative for a cell of the surface.
using CellInset = std::function<double(int, int)>;

struct SideSlackOptions {
  double most_cells = 2.0;  // a side moves out at most this far [cells]
  int bisections = 9;       // steps of the bisection on each side's move
  bool may_overlap = false;  // false: a moved side enters no other piece
  int max_vertices = 8;     // a moved piece keeps at most this many vertices
  Deadline deadline;        // checked before each piece: the pieces left keep their sides
};

// Moves each side of each piece (in order) out along its normal as far as every point it
// adds keeps every cell's inset from that cell's square (exact test) and, unless
// may_overlap, enters no other piece. The pieces must keep the insets already (pieces of
// complete dual squares do); then so do the moved ones.
void AddSideSlack(std::vector<Polygon2d>* pieces, const CellInset& inset_at, double max_inset_cells,
                  const SideSlackOptions& options);

}  // namespace mfp
