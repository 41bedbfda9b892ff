#include "terrain/patch_decomposition.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "planner/base/check.h"
#include "terrain/convex_hull_2d.h"
#include "terrain/surface_layers.h"

namespace mfp {
namespace {

struct LocalGrid {
  int row0 = 0, col0 = 0;  // height map cell of local (0, 0)
  int rows = 0, cols = 0;
  std::vector<uint8_t> cells;
  uint8_t& At(int r, int c) { return cells[static_cast<size_t>(r) * cols + c]; }
  uint8_t At(int r, int c) const { return cells[static_cast<size_t>(r) * cols + c]; }
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

std::vector<Quad2d> DecomposePatch(const HeightMap& hm, const PlanarPatch& patch,
                                   const PatchDecompositionOptions& options) {
  std::vector<Quad2d> quads;
  if (patch.cells.empty()) return quads;
  const double res = hm.resolution_m;
  const double base_cells = options.inset_m / res;
  const double drop_cells = options.drop_inset_m / res;
  // A riser with no uncertainty is kept strictly off (by 0.1 um): a foot disk touching a
  // wall is not on free surface.
  const double riser_cells = (options.riser_inset_m > 0.0 ? options.riser_inset_m : 1e-7) / res;
  const double max_inset_cells = base_cells + std::max(drop_cells, riser_cells);
  // Offsets of the cells whose squares come closer than the largest inset to a cell
  // centre, with that distance [cells].
  struct Offset {
    int dr, dc;
    double dist_cells;
  };
  std::vector<Offset> offsets;
  const int reach = static_cast<int>(std::ceil(max_inset_cells + 0.5));
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      const double ex = std::max(std::abs(dc) - 0.5, 0.0), ey = std::max(std::abs(dr) - 0.5, 0.0);
      const double d = std::sqrt(ex * ex + ey * ey);
      if (d < max_inset_cells - 1e-12 / res) offsets.push_back({dr, dc, d});
    }
  }
  // Patch mask over its bounding box.
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
  auto in_mask = [&](int r, int c) {
    return r >= 0 && r < mask.rows && c >= 0 && c < mask.cols && mask.At(r, c);
  };
  // Each outside cell's inset [cells] over the bounding box plus a ring (-1: a patch
  // cell): the edge uncertainty is added where the patch may end inside its boundary
  // cell next to it - every neighbour unless material rises there (solid_beside).
  const int ring = static_cast<int>(std::ceil(max_inset_cells)) + 2;
  const int ext_rows = mask.rows + 2 * ring, ext_cols = mask.cols + 2 * ring;
  std::vector<double> inset_grid(static_cast<size_t>(ext_rows) * ext_cols, base_cells);
  for (int r = -ring; r < mask.rows + ring; ++r) {
    for (int c = -ring; c < mask.cols + ring; ++c) {
      double& inset = inset_grid[static_cast<size_t>(r + ring) * ext_cols + (c + ring)];
      if (in_mask(r, c)) {
        inset = -1.0;
        continue;
      }
      bool next_to_patch = false, drop = false;
      for (int dr = -1; dr <= 1 && !drop; ++dr) {
        for (int dc = -1; dc <= 1 && !drop; ++dc) {
          if ((dr == 0 && dc == 0) || !in_mask(r + dr, c + dc)) continue;
          next_to_patch = true;
          // From the patch cell (r + dr, c + dc), this cell is neighbour (-dr, -dc).
          const int p = hm.Index(rmin + r + dr, cmin + c + dc);
          drop = options.solid_beside == nullptr ||
                 !((*options.solid_beside)[static_cast<size_t>(p)] & (1u << NeighbourBit(-dr, -dc)));
        }
      }
      if (next_to_patch) inset += drop ? drop_cells : riser_cells;
      // A cell asking no inset (point feet, no margin) still keeps regions off its
      // interior: the side and rotated-rectangle tests below need a positive inset.
      inset = std::max(inset, 1e-6);
    }
  }
  auto inset_at = [&](int r, int c) {
    if (r < -ring || r >= mask.rows + ring || c < -ring || c >= mask.cols + ring) return max_inset_cells;
    return inset_grid[static_cast<size_t>(r + ring) * ext_cols + (c + ring)];
  };
  // Eroded mask: cells whose centre holds a whole foot disk.
  LocalGrid eroded = mask;
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      if (!mask.At(r, c)) continue;
      for (const Offset& o : offsets) {
        const double inset = inset_at(r + o.dr, c + o.dc);
        if (inset >= 0.0 && res * o.dist_cells < res * inset - 1e-12) {
          eroded.At(r, c) = 0;
          break;
        }
      }
    }
  }
  if (mask.rows < 2 || mask.cols < 2) return quads;
  // Dual squares: spanned by the centres of cells (r, c) .. (r + 1, c + 1), all kept.
  LocalGrid dual;
  dual.rows = mask.rows - 1;
  dual.cols = mask.cols - 1;
  dual.cells.assign(static_cast<size_t>(dual.rows) * dual.cols, 0);
  for (int r = 0; r < dual.rows; ++r) {
    for (int c = 0; c < dual.cols; ++c) {
      dual.At(r, c) = eroded.At(r, c) && eroded.At(r + 1, c) && eroded.At(r, c + 1) &&
                      eroded.At(r + 1, c + 1);
    }
  }
  // Local "centre units": x = column offset from the centre of local cell (0, 0).
  const Eigen::Vector2d origin_center = hm.CellCenter(rmin, cmin);
  auto to_world = [&](const Eigen::Vector2d& local) { return origin_center + res * local; };

  const double angle = PrincipalAngleRad(hm, patch);
  const bool use_grid =
      angle < options.axis_snap_rad || angle > M_PI / 2 - options.axis_snap_rad;
  RectangleCoverOptions cover = options.cover;
  if (use_grid) {
    cover.min_rect_cells =
        std::max(1, static_cast<int>(std::ceil(options.min_area_xy_m2 / (res * res) - 1e-9)));
    // Rectangles of complete dual squares end on cell centres; each side then moves out
    // as far as its strip keeps the inset from every cell outside the patch, so regions
    // lose less than the cell quantisation of the inset.
    auto inset_xy = [&](int c, int r) { return inset_at(r, c); };
    for (const CellRect& rect : GreedyRectangleCover(dual.cells, dual.rows, dual.cols, cover)) {
      double x0 = rect.col0, x1 = rect.col0 + rect.cols;
      double y0 = rect.row0, y1 = rect.row0 + rect.rows;
      if (max_inset_cells > 0.0) {
        // -x, +x (mirrored), -y and +y (transposed), each with the sides moved so far.
        x0 -= SideSlack(inset_xy, x0, y0, y1, max_inset_cells);
        x1 += SideSlack([&](int c, int r) { return inset_xy(-c, r); }, -x1, y0, y1, max_inset_cells);
        y0 -= SideSlack([&](int c, int r) { return inset_xy(r, c); }, y0, x0, x1, max_inset_cells);
        y1 += SideSlack([&](int c, int r) { return inset_xy(r, -c); }, -y1, x0, x1, max_inset_cells);
      }
      quads.push_back({to_world({x0, y0}), to_world({x1, y0}), to_world({x1, y1}),
                       to_world({x0, y1})});
    }
    return quads;
  }
  // Rotated frame: u along the principal direction, v across; half-cell sampling.
  const double step = 0.5;
  const Eigen::Vector2d eu(std::cos(angle), std::sin(angle)), ev(-std::sin(angle), std::cos(angle));
  double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
  for (double x : {0.0, double(dual.cols)}) {
    for (double y : {0.0, double(dual.rows)}) {
      const Eigen::Vector2d p(x, y);
      umin = std::min(umin, p.dot(eu));
      umax = std::max(umax, p.dot(eu));
      vmin = std::min(vmin, p.dot(ev));
      vmax = std::max(vmax, p.dot(ev));
    }
  }
  LocalGrid rotated;
  rotated.cols = static_cast<int>(std::ceil((umax - umin) / step));
  rotated.rows = static_cast<int>(std::ceil((vmax - vmin) / step));
  rotated.cells.assign(static_cast<size_t>(rotated.rows) * rotated.cols, 0);
  auto corner = [&](double a, double b) {  // rotated-grid corner -> centre units
    return Eigen::Vector2d(eu * (umin + a * step) + ev * (vmin + b * step));
  };
  for (int b = 0; b < rotated.rows; ++b) {
    for (int a = 0; a < rotated.cols; ++a) {
      double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d p = corner(a + (k & 1), b + (k >> 1));
        xmin = std::min(xmin, p.x());
        xmax = std::max(xmax, p.x());
        ymin = std::min(ymin, p.y());
        ymax = std::max(ymax, p.y());
      }
      const int c0 = static_cast<int>(std::floor(xmin + 1e-9));
      const int c1 = static_cast<int>(std::ceil(xmax - 1e-9));
      const int r0 = static_cast<int>(std::floor(ymin + 1e-9));
      const int r1 = static_cast<int>(std::ceil(ymax - 1e-9));
      if (c0 < 0 || r0 < 0 || c1 > dual.cols || r1 > dual.rows) continue;
      bool inside = true;
      for (int r = r0; r < r1 && inside; ++r) {
        for (int c = c0; c < c1 && inside; ++c) inside = dual.At(r, c);
      }
      rotated.At(b, a) = inside;
    }
  }
  // Cells outside the patch near it (holes, and a ring around the bounding box), with
  // their insets.
  const double inset_cells = max_inset_cells;
  struct Outside {
    int r, c;
    double inset_cells;
  };
  std::vector<Outside> outside;
  for (int r = -ring; r < mask.rows + ring; ++r) {
    for (int c = -ring; c < mask.cols + ring; ++c) {
      if (in_mask(r, c)) continue;
      outside.push_back({r, c, inset_at(r, c)});
    }
  }
  const double cell_area_m2 = step * step * res * res;
  cover.min_rect_cells =
      std::max(1, static_cast<int>(std::ceil(options.min_area_xy_m2 / cell_area_m2 - 1e-9)));
  for (const CellRect& rect :
       GreedyRectangleCover(rotated.cells, rotated.rows, rotated.cols, cover)) {
    double a0 = rect.col0, a1 = rect.col0 + rect.cols;
    double b0 = rect.row0, b1 = rect.row0 + rect.rows;
    // Each side moves out (in rotated-grid steps, up to one cell) while the rectangle keeps
    // the inset from every cell square outside the patch: an exact test, by bisection.
    auto safe = [&](double u0, double u1, double v0, double v1) {
      const std::array<Eigen::Vector2d, 4> quad = {corner(u0, v0), corner(u1, v0), corner(u1, v1), corner(u0, v1)};
      double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
      for (const Eigen::Vector2d& p : quad) {
        xmin = std::min(xmin, p.x());
        xmax = std::max(xmax, p.x());
        ymin = std::min(ymin, p.y());
        ymax = std::max(ymax, p.y());
      }
      for (const Outside& out : outside) {
        const int r = out.r, c = out.c;
        if (r < ymin - inset_cells - 1 || r > ymax + inset_cells + 1 || c < xmin - inset_cells - 1 ||
            c > xmax + inset_cells + 1) {
          continue;
        }
        {
          const double inset_cells = out.inset_cells;
          // Cheap bounds first: the cell centre's distance to the rectangle, +- half a diagonal.
          const Eigen::Vector2d centre(c, r);
          const double a = (centre.dot(eu) - umin) / step, bb = (centre.dot(ev) - vmin) / step;
          const double centre_dist = step * std::hypot(std::max({0.0, u0 - a, a - u1}), std::max({0.0, v0 - bb, bb - v1}));
          if (centre_dist >= inset_cells + 0.7072) continue;
          if (centre_dist < inset_cells - 0.7072) return false;
          const std::array<Eigen::Vector2d, 4> cell = {Eigen::Vector2d(c - 0.5, r - 0.5), Eigen::Vector2d(c + 0.5, r - 0.5),
                                                       Eigen::Vector2d(c + 0.5, r + 0.5), Eigen::Vector2d(c - 0.5, r + 0.5)};
          if (QuadDistance(quad, cell) < inset_cells - 1e-9) return false;
        }
      }
      return true;
    };
    if (inset_cells > 0.0 && safe(a0, a1, b0, b1)) {
      const double most = 1.0 / step;  // one cell, in rotated-grid steps
      auto grow = [&](double* side, double sign) {
        double lo = 0.0, hi = most;
        const double base = *side;
        for (int it = 0; it < 8; ++it) {
          const double mid = 0.5 * (lo + hi);
          *side = base + sign * mid;
          (safe(a0, a1, b0, b1) ? lo : hi) = mid;
        }
        *side = base + sign * lo;
      };
      grow(&a0, -1.0);
      grow(&a1, 1.0);
      grow(&b0, -1.0);
      grow(&b1, 1.0);
    }
    quads.push_back({to_world(corner(a0, b0)), to_world(corner(a1, b0)),
                     to_world(corner(a1, b1)), to_world(corner(a0, b1))});
  }
  return quads;
}

}  // namespace mfp
