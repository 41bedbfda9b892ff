#include <algorithm>
#include <cmath>

#include "terrain/extraction/internal/convex_cover.h"
#include "terrain/extraction/internal/patch_cover.h"

namespace mfp {
namespace {

// The least distance between two parallel lines enclosing a convex polygon: for one of
// its sides, the farthest vertex from that side's line.
double ConvexPolygonWidth(const Polygon2d& polygon) {
  double width = INFINITY;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d edge = polygon[(i + 1) % polygon.size()] - polygon[i];
    const double length = edge.norm();
    if (length == 0.0) continue;
    double farthest = 0.0;
    for (const Eigen::Vector2d& v : polygon) {
      const Eigen::Vector2d to = v - polygon[i];
      farthest = std::max(farthest, std::abs(edge.x() * to.y() - edge.y() * to.x()) / length);
    }
    width = std::min(width, farthest);
  }
  return polygon.size() < 3 ? 0.0 : width;
}

}  // namespace

// Dual square (r, c) spans [c, c + 1] x [r, r + 1] in centre units, the frame CoverInput
// maps to the world; the pieces lie in complete dual squares, so they are safe by the
// argument in patch_decomposition.h. Each side then moves out while what it adds keeps
// every outside cell's inset exactly (AddSideSlack), as the rectangles' sides do.
std::vector<Polygon2d> CoverConvex(const CoverInput& in, const PatchDecompositionOptions& options) {
  ConvexCoverOptions convex;
  convex.cover = options.cover;
  convex.cover.min_rect_cells = MinRectCells(options.min_area_xy_m2, in.res * in.res);
  convex.max_vertices = std::max(3, options.max_piece_vertices);
  convex.shrunk_seeds = options.shrunk_seeds;
  convex.shrunk_seed_min_cells = options.shrunk_seed_min_cells;
  std::vector<Polygon2d> pieces = ConvexCoverOfSquares(in.dual->cells, in.dual->rows, in.dual->cols, convex);
  if (in.max_inset_cells > 0.0) {
    SideSlackOptions slack;
    slack.may_overlap = options.cover.grow_over_covered;
    slack.max_vertices = convex.max_vertices;
    slack.deadline = options.cover.deadline;
    AddSideSlack(&pieces, [&](int r, int c) { return in.inset->At(r, c); }, in.max_inset_cells, slack);
  }
  for (Polygon2d& piece : pieces) {
    for (Eigen::Vector2d& p : piece) p = in.ToWorld(p);
  }
  if (pieces.size() > 1) {
    const double min_width_m = options.min_piece_width_m;
    pieces.erase(std::remove_if(pieces.begin() + 1, pieces.end(),
                                [&](const Polygon2d& piece) { return ConvexPolygonWidth(piece) < min_width_m; }),
                 pieces.end());
  }
  return pieces;
}

}  // namespace mfp
