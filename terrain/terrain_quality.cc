#include "terrain/terrain_quality.h"

#include <cmath>
#include <limits>

namespace mfp {
namespace {

// Where a downward vertical ray through (x, y) first enters the box, or NaN.
double BoxTopAt(const TerrainBox& box, const Eigen::Matrix3d& R, double x_m, double y_m) {
  const double z_start = box.center_world_m.z() + box.size_m.norm() + 1.0;
  const Eigen::Vector3d o = R.transpose() * (Eigen::Vector3d(x_m, y_m, z_start) - box.center_world_m);
  const Eigen::Vector3d d = R.transpose() * Eigen::Vector3d(0, 0, -1);
  double t_in = -std::numeric_limits<double>::infinity();
  double t_out = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double h = 0.5 * box.size_m(a);
    if (std::abs(d(a)) < 1e-12) {
      if (std::abs(o(a)) > h) return std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    double t0 = (-h - o(a)) / d(a), t1 = (h - o(a)) / d(a);
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
  }
  if (t_in > t_out) return std::numeric_limits<double>::quiet_NaN();
  return z_start - t_in;
}

// Points on a region: vertices, edge points and an interior grid (by barycentric fans).
std::vector<Eigen::Vector3d> SampleRegion(const ConvexRegion& region, int per_edge) {
  std::vector<Eigen::Vector3d> pts;
  const auto& v = region.vertices_world_m;
  for (size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector3d& p = v[i];
    const Eigen::Vector3d& q = v[(i + 1) % v.size()];
    for (int k = 0; k < per_edge; ++k) pts.push_back(p + (q - p) * (double(k) / per_edge));
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : v) centroid += p;
  centroid /= static_cast<double>(v.size());
  const size_t boundary = pts.size();
  for (size_t i = 0; i < boundary; ++i) {
    for (int k = 1; k < per_edge; ++k) pts.push_back(centroid + (pts[i] - centroid) * (double(k) / per_edge));
  }
  pts.push_back(centroid);
  return pts;
}

}  // namespace

double TrueTopHeight(const TerrainDescription& terrain, double x_m, double y_m) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const TerrainBox& box : terrain.boxes) {
    const double h = BoxTopAt(box, BoxRotation(box), x_m, y_m);
    if (!std::isnan(h) && !(best >= h)) best = h;
  }
  return best;
}

double MaxDistanceToTopSurfaceM(const std::vector<ConvexRegion>& regions,
                                const TerrainDescription& terrain, double search_radius_m) {
  double worst = 0.0;
  const int n = 6;
  for (const ConvexRegion& region : regions) {
    for (const Eigen::Vector3d& p : SampleRegion(region, 8)) {
      double best = std::numeric_limits<double>::infinity();
      for (int i = -n; i <= n; ++i) {
        for (int j = -n; j <= n; ++j) {
          const Eigen::Vector2d off = search_radius_m / n * Eigen::Vector2d(i, j);
          if (off.norm() > search_radius_m + 1e-12) continue;
          const double top = TrueTopHeight(terrain, p.x() + off.x(), p.y() + off.y());
          if (std::isnan(top)) continue;
          best = std::min(best, std::hypot(off.norm(), p.z() - top));
        }
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

std::vector<FaceCoverage> TopFaceCoverage(const std::vector<ConvexRegion>& regions,
                                          const TerrainDescription& terrain,
                                          double foot_radius_m, double max_slope_rad,
                                          double height_tolerance_m) {
  std::vector<FaceCoverage> out;
  const double step = std::max(0.002, terrain.resolution_m / 4);
  for (size_t b = 0; b < terrain.boxes.size(); ++b) {
    TerrainDescription one;
    one.boxes = {terrain.boxes[b]};
    const std::vector<ConvexRegion> face = TopFaceRegions(one, foot_radius_m, max_slope_rad);
    if (face.empty()) continue;
    const ConvexRegion& f = face.front();
    FaceCoverage cov;
    cov.box = static_cast<int>(b);
    cov.name = terrain.boxes[b].name;
    cov.slope_rad = f.SlopeRad();
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const auto& v : f.vertices_world_m) {
      lo = lo.cwiseMin(v.head<2>());
      hi = hi.cwiseMax(v.head<2>());
    }
    long visible = 0, covered = 0;
    for (double x = lo.x() + step / 2; x < hi.x(); x += step) {
      for (double y = lo.y() + step / 2; y < hi.y(); y += step) {
        bool inside = true;
        for (Eigen::Index j = 0; j + 2 < f.A.rows() && inside; ++j) {
          inside = f.A(j, 0) * x + f.A(j, 1) * y <= f.b(j);
        }
        if (!inside) continue;
        const double z = f.HeightAt(x, y);
        // Visible: nothing higher here or within a foot radius (a foot disk fits).
        bool free = true;
        for (int k = 0; k <= 8 && free; ++k) {
          const double a = k * M_PI / 4;
          const double r = k == 8 ? 0.0 : foot_radius_m;
          const double px = x + r * std::cos(a), py = y + r * std::sin(a);
          const double top = TrueTopHeight(terrain, px, py);
          free = !(top > f.HeightAt(px, py) + 1e-6);
        }
        if (!free) continue;
        ++visible;
        for (const ConvexRegion& region : regions) {
          bool in = true;
          for (Eigen::Index j = 0; j + 2 < region.A.rows() && in; ++j) {
            in = region.A(j, 0) * x + region.A(j, 1) * y <= region.b(j) + 1e-9;
          }
          if (in && std::abs(region.HeightAt(x, y) - z) <= height_tolerance_m) {
            ++covered;
            break;
          }
        }
      }
    }
    cov.visible_area_m2 = visible * step * step;
    if (cov.visible_area_m2 <= M_PI * foot_radius_m * foot_radius_m) continue;
    cov.coverage = visible > 0 ? double(covered) / double(visible) : 0.0;
    out.push_back(cov);
  }
  return out;
}

}  // namespace mfp
