#include "geometry/seen_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
    SeenDisk disk{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), g.resolution_m};
    bool flat = true;
    for (int r = r0; r <= r1 && flat; ++r) {
      for (int c = c0; c <= c1 && flat; ++c) {
        const Eigen::Vector2d cell_lo = g.origin_m + g.resolution_m * Eigen::Vector2d(c, r);
        const Eigen::Vector2d cell_hi = cell_lo + Eigen::Vector2d::Constant(g.resolution_m);
        if ((cell_lo - xy).cwiseMax(xy - cell_hi).cwiseMax(0.0).norm() >= radius) continue;
        const float h = g.height_m[static_cast<size_t>(r) * static_cast<size_t>(g.cols) + static_cast<size_t>(c)];
        flat = std::isfinite(h);
        if (!flat) break;
        disk.low_m = std::min(disk.low_m, static_cast<double>(h));
        disk.high_m = std::max(disk.high_m, static_cast<double>(h));
        flat = disk.high_m - disk.low_m <= g.resolution_m + 1e-6;
      }
    }
    if (flat && disk.low_m <= disk.high_m) return disk;
  }
  return std::nullopt;
}

}  // namespace mfp
