#include "terrain/extraction/internal/patch_decomposition.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "base/check.h"
#include "geometry/convex_hull_2d.h"
#include "terrain/extraction/internal/surface_layers.h"

namespace mfp {
namespace {

struct LocalGrid {
  int row0 = 0, col0 = 0;  // height map cell of local (0, 0)
  int rows = 0, cols = 0;
  std::vector<uint8_t> cells;
  uint8_t& At(int r, int c) { return cells[static_cast<size_t>(r) * cols + c]; }
  uint8_t At(int r, int c) const { return cells[static_cast<size_t>(r) * cols + c]; }
  bool Contains(int r, int c) const { return r >= 0 && r < rows && c >= 0 && c < cols && At(r, c); }
};

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

double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

bool Inside(const std::array<Eigen::Vector2d, 4>& poly, const Eigen::Vector2d& p) {  // counter-clockwise
  for (int i = 0; i < 4; ++i) {
    if (Cross(poly[(i + 1) % 4] - poly[i], p - poly[i]) < 0.0) return false;
  }
  return true;
}

// Distance between two convex quadrilaterals (counter-clockwise); 0 when they overlap.
double QuadDistance(const std::array<Eigen::Vector2d, 4>& p, const std::array<Eigen::Vector2d, 4>& q) {
  for (int i = 0; i < 4; ++i) {
    if (Inside(p, q[i]) || Inside(q, p[i])) return 0.0;
  }
  double d = INFINITY;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d &a = p[i], &b = p[(i + 1) % 4];
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector2d &c = q[j], &e = q[(j + 1) % 4];
      const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, e - a);
      const double d3 = Cross(e - c, a - c), d4 = Cross(e - c, b - c);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return 0.0;
      d = std::min({d, PointSegmentDistance(a, c, e), PointSegmentDistance(b, c, e),
                    PointSegmentDistance(c, a, b), PointSegmentDistance(e, a, b)});
    }
  }
  return d;
}

}  // namespace

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

// The insets of one decomposition, in cells.
struct InsetsInCells {
  double base = 0.0;   // from every cell outside the patch
  double drop = 0.0;   // in addition, next to the patch where its surface may end
  double riser = 0.0;  // in addition, next to the patch where material rises
  double max = 0.0;    // the largest of them all
};

InsetsInCells ToCells(const PatchDecompositionOptions& options, double res) {
  InsetsInCells insets;
  insets.base = options.inset_m / res;
  insets.drop = options.drop_inset_m / res;
  // A riser with no uncertainty is kept strictly off (by 0.1 um): a foot disk touching a
  // wall is not on free surface.
  insets.riser = (options.riser_inset_m > 0.0 ? options.riser_inset_m : 1e-7) / res;
  insets.max = insets.base + std::max(insets.drop, insets.riser);
  return insets;
}

// Offset of a cell whose square comes closer than the largest inset to a cell centre,
// with that distance [cells].
struct Offset {
  int dr, dc;
  double dist_cells;
};

std::vector<Offset> DiskOffsets(double max_inset_cells, double res) {
  std::vector<Offset> offsets;
  const int reach = static_cast<int>(std::ceil(max_inset_cells + 0.5));
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      const double ex = std::max(std::abs(dc) - 0.5, 0.0), ey = std::max(std::abs(dr) - 0.5, 0.0);
      const double d = std::sqrt(ex * ex + ey * ey);
      if (d < max_inset_cells - 1e-12 / res) offsets.push_back({dr, dc, d});
    }
  }
  return offsets;
}

// The patch's cells over its bounding box.
LocalGrid PatchMask(const HeightMap& hm, const PlanarPatch& patch) {
  LocalGrid mask;
  int rmin = hm.rows, rmax = -1, cmin = hm.cols, cmax = -1;
  for (int cell : patch.cells) {
    rmin = std::min(rmin, cell / hm.cols);
    rmax = std::max(rmax, cell / hm.cols);
    cmin = std::min(cmin, cell % hm.cols);
    cmax = std::max(cmax, cell % hm.cols);
  }
  mask.row0 = rmin;
  mask.col0 = cmin;
  mask.rows = rmax - rmin + 1;
  mask.cols = cmax - cmin + 1;
  mask.cells.assign(static_cast<size_t>(mask.rows) * mask.cols, 0);
  for (int cell : patch.cells) mask.At(cell / hm.cols - rmin, cell % hm.cols - cmin) = 1;
  return mask;
}

// Each outside cell's inset [cells] over the mask's bounding box plus a ring (-1: a patch
// cell); beyond the ring, the largest inset.
class InsetField {
 public:
  InsetField(const HeightMap& hm, const LocalGrid& mask, const PatchDecompositionOptions& options,
             const InsetsInCells& insets);
  double At(int r, int c) const {
    if (r < -ring_ || r >= rows_ + ring_ || c < -ring_ || c >= cols_ + ring_) return max_;
    return grid_[static_cast<size_t>(r + ring_) * ext_cols_ + (c + ring_)];
  }
  int ring() const { return ring_; }

 private:
  int ring_, rows_, cols_, ext_cols_;
  double max_;
  std::vector<double> grid_;
};

// The edge uncertainty is added where the patch may end inside its boundary cell next to
// it - every neighbour unless material rises there (solid_beside).
InsetField::InsetField(const HeightMap& hm, const LocalGrid& mask,
                       const PatchDecompositionOptions& options, const InsetsInCells& insets)
    : ring_(static_cast<int>(std::ceil(insets.max)) + 2),
      rows_(mask.rows),
      cols_(mask.cols),
      ext_cols_(mask.cols + 2 * ring_),
      max_(insets.max),
      grid_(static_cast<size_t>(mask.rows + 2 * ring_) * ext_cols_, insets.base) {
  for (int r = -ring_; r < mask.rows + ring_; ++r) {
    for (int c = -ring_; c < mask.cols + ring_; ++c) {
      double& inset = grid_[static_cast<size_t>(r + ring_) * ext_cols_ + (c + ring_)];
      if (mask.Contains(r, c)) {
        inset = -1.0;
        continue;
      }
      bool next_to_patch = false, drop = false;
      for (int dr = -1; dr <= 1 && !drop; ++dr) {
        for (int dc = -1; dc <= 1 && !drop; ++dc) {
          if ((dr == 0 && dc == 0) || !mask.Contains(r + dr, c + dc)) continue;
          next_to_patch = true;
          // From the patch cell (r + dr, c + dc), this cell is neighbour (-dr, -dc).
          const int p = hm.Index(mask.row0 + r + dr, mask.col0 + c + dc);
          drop = options.solid_beside == nullptr ||
                 !((*options.solid_beside)[static_cast<size_t>(p)] & (1u << NeighbourBit(-dr, -dc)));
        }
      }
      if (next_to_patch) inset += drop ? insets.drop : insets.riser;
      // A cell asking no inset (point feet, no margin) still keeps regions off its
      // interior: the side and rotated-rectangle tests need a positive inset.
      inset = std::max(inset, 1e-6);
    }
  }
}

// Eroded mask: cells whose centre holds a whole foot disk.
LocalGrid ErodedMask(const LocalGrid& mask, const InsetField& inset, const std::vector<Offset>& offsets,
                     double res) {
  LocalGrid eroded = mask;
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      if (!mask.At(r, c)) continue;
      for (const Offset& o : offsets) {
        const double cell_inset = inset.At(r + o.dr, c + o.dc);
        if (cell_inset >= 0.0 && res * o.dist_cells < res * cell_inset - 1e-12) {
          eroded.At(r, c) = 0;
          break;
        }
      }
    }
  }
  return eroded;
}

// Dual squares: spanned by the centres of cells (r, c) .. (r + 1, c + 1), all kept.
LocalGrid DualSquares(const LocalGrid& eroded) {
  LocalGrid dual;
  dual.rows = eroded.rows - 1;
  dual.cols = eroded.cols - 1;
  dual.cells.assign(static_cast<size_t>(dual.rows) * dual.cols, 0);
  for (int r = 0; r < dual.rows; ++r) {
    for (int c = 0; c < dual.cols; ++c) {
      dual.At(r, c) = eroded.At(r, c) && eroded.At(r + 1, c) && eroded.At(r, c + 1) &&
                      eroded.At(r + 1, c + 1);
    }
  }
  return dual;
}

// What the two covers share: the patch's local frame ("centre units": x = column offset
// from the centre of local cell (0, 0)) and its safety data.
struct CoverInput {
  const LocalGrid* mask;
  const LocalGrid* dual;
  const InsetField* inset;
  double max_inset_cells;
  double res;
  Eigen::Vector2d origin_center;
  Eigen::Vector2d ToWorld(const Eigen::Vector2d& local) const { return origin_center + res * local; }
};

int MinRectCells(double min_area_xy_m2, double cell_area_m2) {
  return std::max(1, static_cast<int>(std::ceil(min_area_xy_m2 / cell_area_m2 - 1e-9)));
}

// Rectangles of complete dual squares end on cell centres; each side then moves out as
// far as its strip keeps the inset from every cell outside the patch, so regions lose
// less than the cell quantisation of the inset.
std::vector<Quad2d> CoverOnGrid(const CoverInput& in, const PatchDecompositionOptions& options) {
  RectangleCoverOptions cover = options.cover;
  cover.min_rect_cells = MinRectCells(options.min_area_xy_m2, in.res * in.res);
  const double max_inset = in.max_inset_cells;
  auto inset_xy = [&](int c, int r) { return in.inset->At(r, c); };
  std::vector<Quad2d> quads;
  for (const CellRect& rect : GreedyRectangleCover(in.dual->cells, in.dual->rows, in.dual->cols, cover)) {
    double x0 = rect.col0, x1 = rect.col0 + rect.cols;
    double y0 = rect.row0, y1 = rect.row0 + rect.rows;
    if (max_inset > 0.0) {
      // -x, +x (mirrored), -y and +y (transposed), each with the sides moved so far.
      x0 -= SideSlack(inset_xy, x0, y0, y1, max_inset);
      x1 += SideSlack([&](int c, int r) { return inset_xy(-c, r); }, -x1, y0, y1, max_inset);
      y0 -= SideSlack([&](int c, int r) { return inset_xy(r, c); }, y0, x0, x1, max_inset);
      y1 += SideSlack([&](int c, int r) { return inset_xy(r, -c); }, -y1, x0, x1, max_inset);
    }
    quads.push_back({in.ToWorld({x0, y0}), in.ToWorld({x1, y0}), in.ToWorld({x1, y1}), in.ToWorld({x0, y1})});
  }
  return quads;
}

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
  for (int b = 0; b < rotated.rows; ++b) {
    for (int a = 0; a < rotated.cols; ++a) {
      Box2d box;
      for (int k = 0; k < 4; ++k) box.Add(frame.Corner(a + (k & 1), b + (k >> 1)));
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

// The outside cells row by row (rows from -ring, each in column order), so a test near
// a rectangle visits only the rows and columns within reach of it.
struct OutsideCells {
  int row0 = 0;
  std::vector<std::vector<OutsideCell>> rows;
};

OutsideCells ListOutsideCells(const LocalGrid& mask, const InsetField& inset) {
  OutsideCells outside;
  outside.row0 = -inset.ring();
  for (int r = -inset.ring(); r < mask.rows + inset.ring(); ++r) {
    std::vector<OutsideCell>& row = outside.rows.emplace_back();
    for (int c = -inset.ring(); c < mask.cols + inset.ring(); ++c) {
      if (mask.Contains(r, c)) continue;
      row.push_back({r, c, inset.At(r, c)});
    }
  }
  return outside;
}

// Whether a rectangle keeps `out`'s inset from the cell's square (false) or not (true).
bool TooClose(const RotatedFrame& frame, const std::array<Eigen::Vector2d, 4>& quad, const OutsideCell& out,
              double u0, double u1, double v0, double v1) {
  const int r = out.r, c = out.c;
  const double step = RotatedFrame::kStep;
  // Cheap bounds first: the cell centre's distance to the rectangle, +- half a diagonal.
  const Eigen::Vector2d centre(c, r);
  const double a = (centre.dot(frame.eu) - frame.umin) / step, bb = (centre.dot(frame.ev) - frame.vmin) / step;
  const double centre_dist = step * std::hypot(std::max({0.0, u0 - a, a - u1}), std::max({0.0, v0 - bb, bb - v1}));
  if (centre_dist >= out.inset_cells + 0.7072) return false;
  if (centre_dist < out.inset_cells - 0.7072) return true;
  const std::array<Eigen::Vector2d, 4> cell = {Eigen::Vector2d(c - 0.5, r - 0.5), Eigen::Vector2d(c + 0.5, r - 0.5),
                                               Eigen::Vector2d(c + 0.5, r + 0.5), Eigen::Vector2d(c - 0.5, r + 0.5)};
  return QuadDistance(quad, cell) < out.inset_cells - 1e-9;
}

// Whether the rotated rectangle [u0, u1] x [v0, v1] (rotated-grid steps) keeps the inset
// from every cell square outside the patch: an exact test.
bool RotatedRectSafe(const RotatedFrame& frame, const OutsideCells& outside, double max_inset_cells, double u0,
                     double u1, double v0, double v1) {
  const std::array<Eigen::Vector2d, 4> quad = {frame.Corner(u0, v0), frame.Corner(u1, v0),
                                               frame.Corner(u1, v1), frame.Corner(u0, v1)};
  Box2d box;
  for (const Eigen::Vector2d& p : quad) box.Add(p);
  // Cells further than the largest inset plus a cell from the box cannot be too close.
  const double reach = max_inset_cells + 1;
  const int n_rows = static_cast<int>(outside.rows.size());
  const int first = std::max(0, static_cast<int>(std::ceil(box.ymin - reach)) - outside.row0);
  const int last = std::min(n_rows - 1, static_cast<int>(std::floor(box.ymax + reach)) - outside.row0);
  for (int i = first; i <= last; ++i) {
    const std::vector<OutsideCell>& row = outside.rows[static_cast<size_t>(i)];
    auto it = std::lower_bound(row.begin(), row.end(), box.xmin - reach,
                               [](const OutsideCell& cell, double x) { return cell.c < x; });
    for (; it != row.end() && it->c <= box.xmax + reach; ++it) {
      if (TooClose(frame, quad, *it, u0, u1, v0, v1)) return false;
    }
  }
  return true;
}

// Each side of a safe rotated rectangle moves out (in rotated-grid steps, up to one cell)
// while the rectangle stays safe, by bisection.
void GrowRotatedRect(const RotatedFrame& frame, const OutsideCells& outside,
                     double max_inset_cells, double* a0, double* a1, double* b0, double* b1) {
  const double most = 1.0 / RotatedFrame::kStep;  // one cell, in rotated-grid steps
  auto grow = [&](double* side, double sign) {
    double lo = 0.0, hi = most;
    const double base = *side;
    for (int it = 0; it < 8; ++it) {
      const double mid = 0.5 * (lo + hi);
      *side = base + sign * mid;
      (RotatedRectSafe(frame, outside, max_inset_cells, *a0, *a1, *b0, *b1) ? lo : hi) = mid;
    }
    *side = base + sign * lo;
  };
  grow(a0, -1.0);
  grow(a1, 1.0);
  grow(b0, -1.0);
  grow(b1, 1.0);
}

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

// Why an eroded cell lost its foot disk: a cell off the patch within the certification
// radius (centre to centre), or only cells beyond it.
CellFate InsetFate(const InsetField& inset, const std::vector<Offset>& offsets, int r, int c,
                   double certify_radius_cells) {
  for (const Offset& o : offsets) {
    const double cell_inset = inset.At(r + o.dr, c + o.dc);
    if (cell_inset < 0.0 || o.dist_cells >= cell_inset - 1e-12) continue;
    if (std::hypot(o.dr, o.dc) <= certify_radius_cells + 1e-9) return CellFate::kInsetOffPatch;
  }
  return CellFate::kInsetBeyond;
}

bool InsideQuad(const Quad2d& quad, const Eigen::Vector2d& p) {  // counter-clockwise
  for (int i = 0; i < 4; ++i) {
    if (Cross(quad[(i + 1) % 4] - quad[i], p - quad[i]) < -1e-12) return false;
  }
  return true;
}

// Per patch cell: inset (and why), covered by a quad, or neither.
std::vector<CellFate> PatchCellFates(const HeightMap& hm, const PlanarPatch& patch, const LocalGrid& mask,
                                     const LocalGrid& eroded, const InsetField& inset,
                                     const std::vector<Offset>& offsets, double certify_radius_cells,
                                     const std::vector<Quad2d>& quads) {
  std::vector<CellFate> fates;
  fates.reserve(patch.cells.size());
  for (int cell : patch.cells) {
    const int r = cell / hm.cols - mask.row0, c = cell % hm.cols - mask.col0;
    if (!eroded.At(r, c)) {
      fates.push_back(InsetFate(inset, offsets, r, c, certify_radius_cells));
      continue;
    }
    const Eigen::Vector2d centre = hm.CellCenter(cell / hm.cols, cell % hm.cols);
    const bool covered = std::any_of(quads.begin(), quads.end(), [&](const Quad2d& q) { return InsideQuad(q, centre); });
    fates.push_back(covered ? CellFate::kCovered : CellFate::kUncovered);
  }
  return fates;
}

}  // namespace

std::vector<Quad2d> DecomposePatch(const HeightMap& hm, const PlanarPatch& patch,
                                   const PatchDecompositionOptions& options, std::vector<CellFate>* fates) {
  if (fates != nullptr) fates->assign(patch.cells.size(), CellFate::kSmallPatch);
  if (patch.cells.empty()) return {};
  const double res = hm.resolution_m;
  const InsetsInCells insets = ToCells(options, res);
  const LocalGrid mask = PatchMask(hm, patch);
  const InsetField inset(hm, mask, options, insets);
  if (mask.rows < 2 || mask.cols < 2) return {};
  const std::vector<Offset> offsets = DiskOffsets(insets.max, res);
  const LocalGrid eroded = ErodedMask(mask, inset, offsets, res);
  const LocalGrid dual = DualSquares(eroded);
  const CoverInput in{&mask, &dual, &inset, insets.max, res, hm.CellCenter(mask.row0, mask.col0)};
  const double angle = PrincipalAngleRad(hm, patch);
  const bool use_grid = angle < options.axis_snap_rad || angle > M_PI / 2 - options.axis_snap_rad;
  std::vector<Quad2d> quads = use_grid ? CoverOnGrid(in, options) : CoverRotated(in, angle, options);
  if (fates != nullptr) {
    *fates = PatchCellFates(hm, patch, mask, eroded, inset, offsets, insets.base + insets.drop, quads);
  }
  return quads;
}

}  // namespace mfp
