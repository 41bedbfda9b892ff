#include "geometry/seen_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace mfp {
namespace {

// Calls visit(height, cell_centre_xy, plan_distance) for every seen cell within radius_m
// of xy in plan view (distance from xy to the cell's square).
template <typename Visit>
void ForSeenCellsNear(const SurfaceGrid& g, const Eigen::Vector2d& xy, double radius_m, Visit visit) {
  if (g.resolution_m <= 0.0 || g.rows <= 0 || g.cols <= 0) return;
  const Eigen::Vector2d lo = (xy.array() - radius_m - g.origin_m.array()) / g.resolution_m;
  const Eigen::Vector2d hi = (xy.array() + radius_m - g.origin_m.array()) / g.resolution_m;
  const int c0 = std::max(0, static_cast<int>(std::floor(lo.x())));
  const int r0 = std::max(0, static_cast<int>(std::floor(lo.y())));
  const int c1 = std::min(g.cols - 1, static_cast<int>(std::floor(hi.x())));
  const int r1 = std::min(g.rows - 1, static_cast<int>(std::floor(hi.y())));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const float h = g.height_m[static_cast<size_t>(r) * static_cast<size_t>(g.cols) + static_cast<size_t>(c)];
      if (!std::isfinite(h)) continue;
      const Eigen::Vector2d cell_lo = g.origin_m + g.resolution_m * Eigen::Vector2d(c, r);
      const Eigen::Vector2d cell_hi = cell_lo + Eigen::Vector2d::Constant(g.resolution_m);
      const Eigen::Vector2d gap = (cell_lo - xy).cwiseMax(xy - cell_hi).cwiseMax(0.0);
      if (gap.norm() > radius_m) continue;
      visit(static_cast<double>(h), 0.5 * (cell_lo + cell_hi), gap.norm());
    }
  }
}

// The point of the face's polygon nearest to xy in plan view, on the face's plane.
Eigen::Vector3d NearestFacePoint(const ConvexRegion& face, const Eigen::Vector2d& xy) {
  Eigen::Vector2d best = xy;
  if (PlanDistanceToRegion(face, xy) > 0.0) {
    std::vector<Eigen::Vector2d> polygon;
    for (const Eigen::Vector3d& v : face.vertices_world_m) polygon.push_back(v.head<2>());
    best = ClosestBoundaryPoint(polygon, xy);
  }
  return {best.x(), best.y(), face.HeightAt(best.x(), best.y())};
}

// The cells of a disk of one grid (a box of cols x rows from column c0, row r0; -1: not in
// the disk) and the span of their tops, for FlatSeenDisk.
class DiskCells {
 public:
  DiskCells(int c0, int r0, int cols, int rows, double cell_m)
      : c0_(c0), r0_(r0), cols_(cols), rows_(rows), level_(static_cast<size_t>(cols) * static_cast<size_t>(rows), -1),
        top_(level_.size(), 0.0f) {
    span.low_m = std::numeric_limits<double>::infinity();
    span.high_m = -std::numeric_limits<double>::infinity();
    span.cell_m = cell_m;
  }

  // Adds a seen cell's top; false when the tops so far span more than one cell edge.
  bool Add(int c, int r, float top_m) {
    const size_t i = Index(c - c0_, r - r0_);
    level_[i] = 0;
    top_[i] = top_m;
    span.low_m = std::min(span.low_m, static_cast<double>(top_m));
    span.high_m = std::max(span.high_m, static_cast<double>(top_m));
    return span.high_m - span.low_m <= span.cell_m + 1e-6;
  }
  bool seen() const { return span.low_m <= span.high_m; }

  // A riser or curb inside the disk: the tops lie on two levels a cell apart, and the cells
  // of the scarcer level hold a run, a 4-connected set whose bounding box is at least three
  // cells and run_m long (a step's edge across the disk). Scattered pits and bumps of one
  // voxel (sensor noise) make no such run.
  bool HasRun(double run_m) {
    if (!(span.high_m - span.low_m > 0.5 * span.cell_m)) return false;  // one level
    const double middle = 0.5 * (span.low_m + span.high_m);
    int upper = 0, lower = 0;
    for (size_t i = 0; i < level_.size(); ++i) {
      if (level_[i] < 0) continue;
      level_[i] = top_[i] > middle ? 1 : 0;
      (level_[i] == 1 ? upper : lower) += 1;
    }
    const int scarce = upper <= lower ? 1 : 0;
    const double min_run_cells = std::max(3.0, run_m / span.cell_m);
    std::vector<char> visited(level_.size(), 0);
    for (size_t i = 0; i < level_.size(); ++i) {
      if (level_[i] != scarce || visited[i]) continue;
      if (RunLengthCells(i, scarce, &visited) >= min_run_cells) return true;
    }
    return false;
  }

  SeenDisk span;

 private:
  size_t Index(int col, int row) const {
    return static_cast<size_t>(row) * static_cast<size_t>(cols_) + static_cast<size_t>(col);
  }
  // The longer side, in cells, of the bounding box of the 4-connected cells of `level` from `seed`.
  double RunLengthCells(size_t seed, int level, std::vector<char>* visited) const {
    int col_lo = cols_, col_hi = -1, row_lo = rows_, row_hi = -1;
    std::vector<size_t> stack{seed};
    (*visited)[seed] = 1;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      const int col = static_cast<int>(i % static_cast<size_t>(cols_)), row = static_cast<int>(i / static_cast<size_t>(cols_));
      col_lo = std::min(col_lo, col), col_hi = std::max(col_hi, col);
      row_lo = std::min(row_lo, row), row_hi = std::max(row_hi, row);
      for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int nc = col + dc, nr = row + dr;
        if (nc < 0 || nr < 0 || nc >= cols_ || nr >= rows_) continue;
        const size_t n = Index(nc, nr);
        if (level_[n] != level || (*visited)[n]) continue;
        (*visited)[n] = 1;
        stack.push_back(n);
      }
    }
    return static_cast<double>(std::max(col_hi - col_lo, row_hi - row_lo) + 1);
  }

  int c0_, r0_, cols_, rows_;
  std::vector<int> level_;  // per cell of the box: -1 outside the disk, else 0 lower, 1 upper (HasRun)
  std::vector<float> top_;
};

}  // namespace

bool OnSeenSurface(const SeenSurface& surface, const Eigen::Vector3d& p, double tolerance_m) {
  for (const ConvexRegion& face : surface.faces) {
    if (PlanDistanceToRegion(face, p.head<2>()) > tolerance_m) continue;
    if (std::abs(NearestFacePoint(face, p.head<2>()).z() - p.z()) <= tolerance_m + face.plane_tolerance_m) return true;
  }
  for (const SurfaceGrid& g : surface.grids) {
    bool on = false;
    ForSeenCellsNear(g, p.head<2>(), tolerance_m, [&](double h, const Eigen::Vector2d&, double) {
      on = on || (p.z() <= h + tolerance_m && p.z() >= h - g.resolution_m - tolerance_m);
    });
    if (on) return true;
  }
  return false;
}

NearestSurfacePoint NearestSeenSurface(const SeenSurface& surface, const Eigen::Vector3d& p, double search_radius_m) {
  NearestSurfacePoint best;
  auto offer = [&](const Eigen::Vector3d& q) {
    const double d = (q - p).norm();
    if (!best.found || d < best.distance_m) best = NearestSurfacePoint{true, q, d};
  };
  for (const ConvexRegion& face : surface.faces) {
    if (PlanDistanceToRegion(face, p.head<2>()) <= search_radius_m) offer(NearestFacePoint(face, p.head<2>()));
  }
  for (const SurfaceGrid& g : surface.grids) {
    ForSeenCellsNear(g, p.head<2>(), search_radius_m, [&](double h, const Eigen::Vector2d& centre, double) {
      offer(Eigen::Vector3d(centre.x(), centre.y(), h));
    });
  }
  return best;
}

std::optional<double> HighestSeenSurfaceAt(const SeenSurface& surface, const Eigen::Vector2d& xy) {
  std::optional<double> best;
  auto offer = [&](double h) { best = best ? std::max(*best, h) : h; };
  for (const ConvexRegion& face : surface.faces) {
    if (PlanDistanceToRegion(face, xy) <= 0.0) offer(face.HeightAt(xy.x(), xy.y()));
  }
  for (const SurfaceGrid& g : surface.grids) {
    ForSeenCellsNear(g, xy, 0.0, [&](double h, const Eigen::Vector2d&, double) { offer(h); });
  }
  return best;
}

std::optional<SeenDisk> FlatSeenDisk(const SeenSurface& surface, const Eigen::Vector2d& xy, double radius_m) {
  for (const SurfaceGrid& g : surface.grids) {
    if (g.resolution_m <= 0.0 || g.rows <= 0 || g.cols <= 0) continue;
    const double radius = radius_m + g.resolution_m;
    const Eigen::Vector2d lo = (xy.array() - radius - g.origin_m.array()) / g.resolution_m;
    const Eigen::Vector2d hi = (xy.array() + radius - g.origin_m.array()) / g.resolution_m;
    // Compared in double before the casts: a far point (any finite request) must not overflow an int.
    if (!(lo.x() >= 0.0 && lo.y() >= 0.0 && hi.x() < g.cols && hi.y() < g.rows)) continue;  // the disk leaves the grid
    const int c0 = static_cast<int>(std::floor(lo.x())), r0 = static_cast<int>(std::floor(lo.y()));
    const int c1 = static_cast<int>(std::floor(hi.x())), r1 = static_cast<int>(std::floor(hi.y()));
    DiskCells disk(c0, r0, c1 - c0 + 1, r1 - r0 + 1, g.resolution_m);
    bool flat = true;
    for (int r = r0; r <= r1 && flat; ++r) {
      for (int c = c0; c <= c1 && flat; ++c) {
        const Eigen::Vector2d cell_lo = g.origin_m + g.resolution_m * Eigen::Vector2d(c, r);
        const Eigen::Vector2d cell_hi = cell_lo + Eigen::Vector2d::Constant(g.resolution_m);
        if ((cell_lo - xy).cwiseMax(xy - cell_hi).cwiseMax(0.0).norm() >= radius) continue;
        const float h = g.height_m[static_cast<size_t>(r) * static_cast<size_t>(g.cols) + static_cast<size_t>(c)];
        flat = std::isfinite(h) && disk.Add(c, r, h);
      }
    }
    if (flat && disk.seen() && !disk.HasRun(radius_m)) return disk.span;
  }
  return std::nullopt;
}

}  // namespace mfp
