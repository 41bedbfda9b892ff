#include "terrain/quality/terrain_quality.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "geometry/plan_bounds.h"

namespace mfp {
namespace {

// Where a downward vertical ray through (x, y) first enters the box, or NaN.
double BoxTopAt(const TerrainBox& box, const Eigen::Matrix3d& R, double x_m, double y_m) {
  const double z_start = box.center_world_m.z() + box.size_m.norm() + 1.0;
  double t_in = 0.0, t_out = 0.0;
  if (!RayBoxInterval(box, R, Eigen::Vector3d(x_m, y_m, z_start), Eigen::Vector3d(0, 0, -1), 1e-12, &t_in, &t_out)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
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

// The vertical extent [z_bottom, z_top] of a box over (x, y); false when it misses.
bool VerticalExtent(const TerrainBox& box, const Eigen::Matrix3d& R, double x_m, double y_m,
                    double* z_bottom, double* z_top) {
  const double top = BoxTopAt(box, R, x_m, y_m);
  if (std::isnan(top)) return false;
  // The exit of the downward ray: the entry of the upward ray from below.
  const double z_start = box.center_world_m.z() - box.size_m.norm() - 1.0;
  const Eigen::Vector3d o = R.transpose() * (Eigen::Vector3d(x_m, y_m, z_start) - box.center_world_m);
  const Eigen::Vector3d d = R.transpose() * Eigen::Vector3d(0, 0, 1);
  double t_in = -std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double h = 0.5 * box.size_m(a);
    if (std::abs(d(a)) < 1e-12) continue;
    const double t0 = (-h - o(a)) / d(a), t1 = (h - o(a)) / d(a);
    t_in = std::max(t_in, std::min(t0, t1));
  }
  *z_top = top;
  *z_bottom = z_start + t_in;
  return true;
}

// True when some box holds a point of the vertical segment (z_lo, z_hi] over (x, y).
bool Occupied(const TerrainDescription& terrain, double x_m, double y_m, double z_lo, double z_hi) {
  for (const TerrainBox& box : terrain.boxes) {
    double bottom, top;
    if (VerticalExtent(box, BoxRotation(box), x_m, y_m, &bottom, &top) && top > z_lo && bottom < z_hi) {
      return true;
    }
  }
  return false;
}

}  // namespace

double TrueSurfaceBelow(const TerrainDescription& terrain, double x_m, double y_m, double z_from_m) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const TerrainBox& box : terrain.boxes) {
    double bottom, top;
    if (!VerticalExtent(box, BoxRotation(box), x_m, y_m, &bottom, &top)) continue;
    if (bottom < z_from_m && top > z_from_m) return std::numeric_limits<double>::quiet_NaN();
    if (top <= z_from_m && !(best >= top)) best = top;
  }
  return best;
}

bool OnTrueTopSurface(const TerrainDescription& terrain, const Eigen::Vector3d& p, double radius_m,
                      double height_tolerance_m, const Eigen::Vector3d& normal_world) {
  const Eigen::Vector3d nrm = normal_world.normalized();
  // The disk lies in the plane (a foot's margin is measured along the surface): an
  // orthonormal pair spanning it. A horizontal disk projected onto a tilted plane would
  // ask 1 / cos(slope) times the margin along the tilt.
  const Eigen::Vector3d u = (Eigen::Vector3d::UnitX() - nrm.x() * nrm).normalized();
  const Eigen::Vector3d v = nrm.cross(u);
  const int rings = radius_m > 0.0 ? 2 : 0;
  for (int ring = 0; ring <= rings; ++ring) {
    const double r = rings > 0 ? radius_m * ring / rings : 0.0;
    const int count = ring == 0 ? 1 : 8 * ring;
    for (int k = 0; k < count; ++k) {
      const double a = 2 * M_PI * k / count;
      const Eigen::Vector3d q = p + r * (std::cos(a) * u + std::sin(a) * v);
      const double x = q.x(), y = q.y(), z = q.z();
      const double below = TrueSurfaceBelow(terrain, x, y, z + height_tolerance_m);
      if (!(below >= z - height_tolerance_m)) return false;
    }
  }
  return true;
}

bool FootOnTrueSurface(const TerrainDescription& terrain, const Eigen::Vector3d& p, double margin_m,
                       double max_slope_rad, double height_tol_m) {
  // The face under the foot centre: its slope and the plane the foot's disk lies on.
  const TerrainBox* face = nullptr;
  for (const TerrainBox& box : terrain.boxes) {
    const Eigen::Matrix3d r = BoxRotation(box);
    if (r(2, 2) < std::cos(max_slope_rad)) continue;  // local +z is the top face only when it points up enough
    const Eigen::Vector3d q = r.transpose() * (p - box.center_world_m);
    if (std::abs(q.z() - box.size_m.z() / 2) > height_tol_m) continue;
    if (std::abs(q.x()) > box.size_m.x() / 2 || std::abs(q.y()) > box.size_m.y() / 2) continue;
    face = &box;
    break;
  }
  if (face == nullptr) return false;
  // The margin disk on real surface: abutting faces within the height tolerance are one
  // surface (a foot may stand across the seam of two treads of one height); a drop or a
  // gap within the margin fails.
  return OnTrueTopSurface(terrain, p, margin_m, height_tol_m, BoxRotation(*face).col(2));
}

RegionSoundness MeasureSoundness(const std::vector<ConvexRegion>& regions,
                                 const TerrainDescription& terrain, double radius_m,
                                 double height_tolerance_m) {
  RegionSoundness out;
  for (const ConvexRegion& region : regions) {
    for (const Eigen::Vector3d& p : SampleRegion(region, 8)) {
      ++out.samples;
      if (OnTrueTopSurface(terrain, p, radius_m, height_tolerance_m, region.normal_world)) {
        ++out.sound;
      } else {
        out.worst_point = p;
      }
    }
  }
  out.fraction = out.samples > 0 ? double(out.sound) / out.samples : 1.0;
  return out;
}

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
  CoverageOptions options;
  options.inset_m = foot_radius_m;
  options.disk_radius_m = foot_radius_m;
  options.max_slope_rad = max_slope_rad;
  options.height_tolerance_m = height_tolerance_m;
  return TopFaceCoverage(regions, terrain, options);
}

std::vector<FaceCoverage> TopFaceCoverage(const std::vector<ConvexRegion>& regions,
                                          const TerrainDescription& terrain,
                                          const CoverageOptions& options) {
  const double foot_radius_m = options.disk_radius_m;
  const double height_tolerance_m = options.height_tolerance_m;
  std::vector<FaceCoverage> out;
  const double step = std::max(0.002, terrain.resolution_m / 4);
  for (size_t b = 0; b < terrain.boxes.size(); ++b) {
    if (!options.only_face.empty() && terrain.boxes[b].name != options.only_face) continue;
    TerrainDescription one;
    one.boxes = {terrain.boxes[b]};
    const std::vector<ConvexRegion> face = TopFaceRegions(one, options.inset_m, options.max_slope_rad);
    if (face.empty()) continue;
    const ConvexRegion& f = face.front();
    FaceCoverage cov;
    cov.box = static_cast<int>(b);
    cov.name = terrain.boxes[b].name;
    cov.slope_rad = f.SlopeRad();
    const Eigen::AlignedBox2d bounds = PlanBounds(f);
    const Eigen::Vector2d lo = bounds.min(), hi = bounds.max();
    long visible = 0, covered = 0;
    for (double x = lo.x() + step / 2; x < hi.x(); x += step) {
      for (double y = lo.y() + step / 2; y < hi.y(); y += step) {
        bool inside = true;
        for (Eigen::Index j = 0; j + 2 < f.A.rows() && inside; ++j) {
          inside = f.A(j, 0) * x + f.A(j, 1) * y <= f.b(j);
        }
        if (!inside) continue;
        const double z = f.HeightAt(x, y);
        // Visible: no box within the clearance above here or within the disk.
        bool free = true;
        for (int k = 0; k <= 8 && free; ++k) {
          const double a = k * M_PI / 4;
          const double r = k == 8 ? 0.0 : foot_radius_m;
          const double px = x + r * std::cos(a), py = y + r * std::sin(a);
          const double fz = f.HeightAt(px, py);
          free = !Occupied(terrain, px, py, fz + 1e-6, fz + options.clearance_m);
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
