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

// True when a cell's square comes closer than radius_m to xy in plan view (a disk's cell).
bool InDisk(const SurfaceGrid& g, int col, int row, const Eigen::Vector2d& xy, double radius_m) {
  const Eigen::Vector2d cell_lo = g.origin_m + g.resolution_m * Eigen::Vector2d(col, row);
  const Eigen::Vector2d cell_hi = cell_lo + Eigen::Vector2d::Constant(g.resolution_m);
  return (cell_lo - xy).cwiseMax(xy - cell_hi).cwiseMax(0.0).norm() < radius_m;
}

// A disk of seen cells (columns c0..c1, rows r0..r1 of g, those within radius_m of xy) whose
// tops lie on two levels a cell apart, split at middle_m: true when the cells of the scarcer
// level hold a run, a 4-connected set whose bounding box is at least three cells and run_m
// long (a one-voxel riser, curb or groove across the disk). Scattered pits and bumps of one
// voxel (sensor noise) make no such run.
bool HasRun(const SurfaceGrid& g, const Eigen::Vector2d& xy, double radius_m, int c0, int r0, int c1, int r1,
            double middle_m, double run_m) {
  const int cols = c1 - c0 + 1, rows = r1 - r0 + 1;
  std::vector<int> level(static_cast<size_t>(cols) * static_cast<size_t>(rows), -1);  // -1: not in the disk
  int upper = 0, lower = 0;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (!InDisk(g, c, r, xy, radius_m)) continue;
      const float h = g.height_m[static_cast<size_t>(r) * static_cast<size_t>(g.cols) + static_cast<size_t>(c)];
      const int up = h > middle_m ? 1 : 0;
      level[static_cast<size_t>(r - r0) * static_cast<size_t>(cols) + static_cast<size_t>(c - c0)] = up;
      (up == 1 ? upper : lower) += 1;
    }
  }
  const int scarce = upper <= lower ? 1 : 0;
  const double min_run_cells = std::max(3.0, run_m / g.resolution_m);
  std::vector<char> visited(level.size(), 0);
  std::vector<size_t> stack;
  for (size_t seed = 0; seed < level.size(); ++seed) {
    if (level[seed] != scarce || visited[seed]) continue;
    int col_lo = cols, col_hi = -1, row_lo = rows, row_hi = -1;
    stack.assign(1, seed);
    visited[seed] = 1;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      const int col = static_cast<int>(i % static_cast<size_t>(cols)), row = static_cast<int>(i / static_cast<size_t>(cols));
      col_lo = std::min(col_lo, col), col_hi = std::max(col_hi, col);
      row_lo = std::min(row_lo, row), row_hi = std::max(row_hi, row);
      for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int nc = col + dc, nr = row + dr;
        if (nc < 0 || nr < 0 || nc >= cols || nr >= rows) continue;
        const size_t n = static_cast<size_t>(nr) * static_cast<size_t>(cols) + static_cast<size_t>(nc);
        if (level[n] != scarce || visited[n]) continue;
        visited[n] = 1;
        stack.push_back(n);
      }
    }
    if (std::max(col_hi - col_lo, row_hi - row_lo) + 1 >= min_run_cells) return true;
  }
  return false;
}

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

std::optional<SeenDisk> FlatSeenDisk(const SeenSurface& surface, const Eigen::Vector2d& xy, double radius_m,
                                     bool refuse_runs) {
  for (const SurfaceGrid& g : surface.grids) {
    if (g.resolution_m <= 0.0 || g.rows <= 0 || g.cols <= 0) continue;
    const double radius = radius_m + g.resolution_m;
    const Eigen::Vector2d lo = (xy.array() - radius - g.origin_m.array()) / g.resolution_m;
    const Eigen::Vector2d hi = (xy.array() + radius - g.origin_m.array()) / g.resolution_m;
    // Compared in double before the casts: a far point (any finite request) must not overflow an int.
    if (!(lo.x() >= 0.0 && lo.y() >= 0.0 && hi.x() < g.cols && hi.y() < g.rows)) continue;  // the disk leaves the grid
    const int c0 = static_cast<int>(std::floor(lo.x())), r0 = static_cast<int>(std::floor(lo.y()));
    const int c1 = static_cast<int>(std::floor(hi.x())), r1 = static_cast<int>(std::floor(hi.y()));
    SeenDisk disk{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), g.resolution_m};
    bool flat = true;
    for (int r = r0; r <= r1 && flat; ++r) {
      for (int c = c0; c <= c1 && flat; ++c) {
        if (!InDisk(g, c, r, xy, radius)) continue;
        const float h = g.height_m[static_cast<size_t>(r) * static_cast<size_t>(g.cols) + static_cast<size_t>(c)];
        flat = std::isfinite(h);
        if (!flat) break;
        disk.low_m = std::min(disk.low_m, static_cast<double>(h));
        disk.high_m = std::max(disk.high_m, static_cast<double>(h));
        flat = disk.high_m - disk.low_m <= g.resolution_m + 1e-6;
      }
    }
    if (!flat || !(disk.low_m <= disk.high_m)) continue;
    // Two levels: noise, or a run across the disk (looked for only then).
    const bool two_levels = disk.high_m - disk.low_m > 0.5 * g.resolution_m;
    if (refuse_runs && two_levels &&
        HasRun(g, xy, radius, c0, r0, c1, r1, 0.5 * (disk.low_m + disk.high_m), radius_m)) {
      continue;
    }
    return disk;
  }
  return std::nullopt;
}

}  // namespace mfp
