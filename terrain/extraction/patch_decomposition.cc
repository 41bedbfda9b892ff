#include "terrain/extraction/internal/patch_decomposition.h"

#include <algorithm>
#include <cmath>

#include "geometry/convex_hull_2d.h"
#include "terrain/extraction/internal/patch_cover.h"
#include "terrain/extraction/internal/patch_safety.h"

namespace mfp {

double PrincipalAngleRad(const HeightMap& hm, const PlanarPatch& patch) {
  // Only boundary-relevant points matter: the corners of each cell square (in cells).
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(patch.cells.size());
  for (int cell : patch.cells) {
    pts.emplace_back(cell % hm.cols, cell / hm.cols);
  }
  const std::vector<Eigen::Vector2d> hull = ConvexHull2d(pts);
  if (hull.size() < 3) return 0.0;
  double best_area = INFINITY, best_angle = 0.0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d e = (hull[(i + 1) % hull.size()] - hull[i]).normalized();
    const Eigen::Vector2d n(-e.y(), e.x());
    double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    for (const Eigen::Vector2d& p : hull) {
      umin = std::min(umin, p.dot(e));
      umax = std::max(umax, p.dot(e));
      vmin = std::min(vmin, p.dot(n));
      vmax = std::max(vmax, p.dot(n));
    }
    // Cells have width: add one cell to each side so thin patches compare fairly.
    const double area = (umax - umin + 1.0) * (vmax - vmin + 1.0);
    if (area < best_area - 1e-9) {
      best_area = area;
      best_angle = std::atan2(e.y(), e.x());
    }
  }
  best_angle = std::fmod(best_angle, M_PI / 2);
  if (best_angle < 0) best_angle += M_PI / 2;
  return best_angle;
}

namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Why an eroded cell lost its foot disk: a cell off the patch within the certification
// radius (centre to centre), or only cells beyond it.
CellFate InsetFate(const InsetField& inset, const std::vector<DiskOffset>& offsets, int r, int c,
                   double certify_radius_cells) {
  for (const DiskOffset& o : offsets) {
    const double cell_inset = inset.At(r + o.dr, c + o.dc);
    if (cell_inset < 0.0 || o.dist_cells >= cell_inset - 1e-12) continue;
    if (std::hypot(o.dr, o.dc) <= certify_radius_cells + 1e-9) return CellFate::kInsetOffPatch;
  }
  return CellFate::kInsetBeyond;
}

bool InsidePolygon(const Polygon2d& polygon, const Eigen::Vector2d& p) {  // counter-clockwise
  for (size_t i = 0; i < polygon.size(); ++i) {
    if (Cross(polygon[(i + 1) % polygon.size()] - polygon[i], p - polygon[i]) < -1e-12) return false;
  }
  return true;
}

std::vector<Polygon2d> AsPolygons(const std::vector<Quad2d>& quads) {
  std::vector<Polygon2d> polygons;
  polygons.reserve(quads.size());
  for (const Quad2d& q : quads) polygons.emplace_back(q.begin(), q.end());
  return polygons;
}

// Per patch cell: inset (and why), covered by a quad, or neither.
std::vector<CellFate> PatchCellFates(const HeightMap& hm, const PlanarPatch& patch, const LocalGrid& mask,
                                     const LocalGrid& eroded, const InsetField& inset,
                                     const std::vector<DiskOffset>& offsets, double certify_radius_cells,
                                     const std::vector<Polygon2d>& polygons) {
  std::vector<CellFate> fates;
  fates.reserve(patch.cells.size());
  for (int cell : patch.cells) {
    const int r = cell / hm.cols - mask.row0, c = cell % hm.cols - mask.col0;
    if (!eroded.At(r, c)) {
      fates.push_back(InsetFate(inset, offsets, r, c, certify_radius_cells));
      continue;
    }
    const Eigen::Vector2d centre = hm.CellCenter(cell / hm.cols, cell % hm.cols);
    const bool covered =
        std::any_of(polygons.begin(), polygons.end(), [&](const Polygon2d& q) { return InsidePolygon(q, centre); });
    fates.push_back(covered ? CellFate::kCovered : CellFate::kUncovered);
  }
  return fates;
}

// How many kept (eroded) cells have their centre in a polygon.
int CentresCovered(const HeightMap& hm, const LocalGrid& eroded, const std::vector<Polygon2d>& polygons) {
  std::vector<uint8_t> covered(eroded.cells.size(), 0);
  const double res = hm.resolution_m;
  const Eigen::Vector2d origin = hm.CellCenter(eroded.row0, eroded.col0);
  for (const Polygon2d& polygon : polygons) {
    Eigen::Vector2d lo = polygon.front(), hi = polygon.front();
    for (const Eigen::Vector2d& p : polygon) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const int c0 = std::max(0, static_cast<int>(std::floor((lo.x() - origin.x()) / res)));
    const int c1 = std::min(eroded.cols - 1, static_cast<int>(std::ceil((hi.x() - origin.x()) / res)));
    const int r0 = std::max(0, static_cast<int>(std::floor((lo.y() - origin.y()) / res)));
    const int r1 = std::min(eroded.rows - 1, static_cast<int>(std::ceil((hi.y() - origin.y()) / res)));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const size_t i = static_cast<size_t>(r) * eroded.cols + c;
        if (eroded.cells[i] && !covered[i]) covered[i] = InsidePolygon(polygon, origin + res * Eigen::Vector2d(c, r));
      }
    }
  }
  return static_cast<int>(std::count(covered.begin(), covered.end(), 1));
}

// Whether the pieces alone cover the patch: at least convex_alone_cells kept cells, and an
// outline of kept cells (those with a 4-neighbour not kept) at least convex_alone_outline
// times a square's of as many cells and convex_alone_outline_share of the kept cells: a
// face of boxes (a square's outline, or a long smooth floor's small share) compares.
bool ConvexAlone(const LocalGrid& eroded, int kept, const PatchDecompositionOptions& options) {
  if (kept < options.convex_alone_cells) return false;
  int outline = 0;
  for (int r = 0; r < eroded.rows; ++r) {
    for (int c = 0; c < eroded.cols; ++c) {
      if (eroded.At(r, c) && (!eroded.Contains(r - 1, c) || !eroded.Contains(r + 1, c) ||
                              !eroded.Contains(r, c - 1) || !eroded.Contains(r, c + 1))) {
        ++outline;
      }
    }
  }
  return outline >= options.convex_alone_outline * 4.0 * std::sqrt(static_cast<double>(kept)) &&
         outline >= options.convex_alone_outline_share * kept;
}

}  // namespace

std::vector<Polygon2d> DecomposePatch(const HeightMap& hm, const PlanarPatch& patch,
                                   const PatchDecompositionOptions& options, std::vector<CellFate>* fates,
                                   bool* pieces_alone) {
  if (fates != nullptr) fates->assign(patch.cells.size(), CellFate::kSmallPatch);
  if (pieces_alone != nullptr) *pieces_alone = false;
  if (patch.cells.empty()) return {};
  const double res = hm.resolution_m;
  const InsetsInCells insets = InsetsToCells(options, res);
  const LocalGrid mask = PatchMask(hm, patch, options);
  if (mask.rows < 2 || mask.cols < 2) return {};
  const InsetField inset(hm, mask, options, insets);
  const std::vector<DiskOffset> offsets = DiskOffsets(insets.max, res);
  const LocalGrid eroded = ErodedMask(mask, inset, offsets, res);
  const LocalGrid dual = DualSquares(eroded);
  const CoverInput in{&mask, &dual, &inset, insets.max, res, hm.CellCenter(mask.row0, mask.col0)};
  const auto kept =
      static_cast<int>(std::count_if(eroded.cells.begin(), eroded.cells.end(), [](uint8_t v) { return v != 0; }));
  std::vector<Polygon2d> polygons;
  // A large ragged patch: the pieces alone (the rectangles would be computed only to
  // lose); should they find nothing, the rectangles below.
  const bool alone = options.convex_pieces && ConvexAlone(eroded, kept, options);
  if (alone) polygons = CoverConvex(in, options);
  if (pieces_alone != nullptr) *pieces_alone = !polygons.empty();
  if (polygons.empty()) {
    const double angle = PrincipalAngleRad(hm, patch);
    const bool use_grid = angle < options.axis_snap_rad || angle > M_PI / 2 - options.axis_snap_rad;
    polygons = AsPolygons(use_grid ? CoverOnGrid(in, options) : CoverRotated(in, angle, options));
  }
  if (options.convex_pieces && !alone) {
    // The rectangles reach past the dual squares up to the exact inset, the convex pieces
    // follow a ragged outline: keep the pieces only where they hold more kept cells'
    // centres (by more than 1 % of the kept cells), so no patch loses. Where the rectangles
    // leave at most that 1 % uncovered the pieces cannot win: they are not computed.
    const int by_rects = CentresCovered(hm, eroded, polygons);
    if (kept - by_rects > kept / 100) {
      std::vector<Polygon2d> pieces = CoverConvex(in, options);
      const int by_pieces = CentresCovered(hm, eroded, pieces);
      if (by_pieces > by_rects + kept / 100) polygons = std::move(pieces);
    }
  }
  if (fates != nullptr) {
    *fates = PatchCellFates(hm, patch, mask, eroded, inset, offsets, insets.base + insets.drop, polygons);
  }
  return polygons;
}

}  // namespace mfp
