#include "geometry/convex_region.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "base/check.h"

namespace mfp {
namespace {

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

std::string RegionName(int id) { return "region " + std::to_string(id); }

}  // namespace

double ConvexRegion::HeightAt(double x_m, double y_m) const {
  MFP_CHECK(!vertices_world_m.empty());
  const Eigen::Vector3d& p0 = vertices_world_m.front();
  // n . (f - p0) = 0  =>  z = p0.z - (n_x (x - p0.x) + n_y (y - p0.y)) / n_z
  return p0.z() - (normal_world.x() * (x_m - p0.x()) + normal_world.y() * (y_m - p0.y())) /
                      normal_world.z();
}

double ConvexRegion::SlopeRad() const {
  return std::acos(std::min(1.0, std::abs(normal_world.z())));
}

ConvexRegion MakeRegionFromPolygon(int id, const std::vector<Eigen::Vector3d>& vertices_world_m,
                                   double plane_tolerance_m) {
  const std::string name = RegionName(id);
  if (!std::isfinite(plane_tolerance_m) || plane_tolerance_m < 0.0) {
    throw InputError(name + ": plane tolerance must be finite and >= 0");
  }
  for (const Eigen::Vector3d& v : vertices_world_m) {
    if (!v.allFinite()) throw InputError(name + ": a vertex is not a finite number");
  }
  // Drop duplicates (closing vertex repeated, etc.).
  std::vector<Eigen::Vector3d> pts;
  for (const Eigen::Vector3d& v : vertices_world_m) {
    if (pts.empty() || (v.head<2>() - pts.back().head<2>()).norm() > 1e-9) pts.push_back(v);
  }
  while (pts.size() > 1 && (pts.front().head<2>() - pts.back().head<2>()).norm() <= 1e-9) {
    pts.pop_back();
  }
  if (pts.size() < 3) {
    throw InputError(name + ": needs at least 3 distinct vertices, has " +
                     std::to_string(pts.size()));
  }
  // Plane by least squares: z = a x + b y + c.
  Eigen::MatrixXd M(pts.size(), 3);
  Eigen::VectorXd z(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    M.row(i) << pts[i].x(), pts[i].y(), 1.0;
    z(i) = pts[i].z();
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M);
  if (qr.rank() < 3) {
    throw InputError(name + ": vertices are collinear or the polygon is vertical");
  }
  const Eigen::Vector3d plane = qr.solve(z);
  const double residual = (M * plane - z).cwiseAbs().maxCoeff();
  if (residual > std::max(plane_tolerance_m, 1e-6)) {
    std::ostringstream msg;
    msg << name << ": vertices are not coplanar (off the plane by " << residual
        << " m, tolerance " << plane_tolerance_m << " m)";
    throw InputError(msg.str());
  }
  // Winding: make it counter-clockwise seen from above.
  double twice_area_xy = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    twice_area_xy += Cross2(pts[i].head<2>(), pts[(i + 1) % pts.size()].head<2>());
  }
  if (twice_area_xy < 0.0) std::reverse(pts.begin(), pts.end());
  // Drop collinear vertices, then require strict convexity.
  std::vector<Eigen::Vector3d> hull;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d prev = pts[(i + pts.size() - 1) % pts.size()].head<2>();
    const Eigen::Vector2d cur = pts[i].head<2>();
    const Eigen::Vector2d next = pts[(i + 1) % pts.size()].head<2>();
    const double turn = Cross2(cur - prev, next - cur);
    const double scale = (cur - prev).norm() * (next - cur).norm();
    if (turn < -1e-9 * scale) throw InputError(name + ": polygon is not convex");
    if (turn > 1e-9 * scale) hull.push_back(pts[i]);
  }
  if (hull.size() < 3) throw InputError(name + ": polygon has no area");

  ConvexRegion region;
  region.id = id;
  region.plane_tolerance_m = plane_tolerance_m;
  Eigen::Vector3d normal(-plane.x(), -plane.y(), 1.0);
  region.normal_world = normal.normalized();
  const size_t n = hull.size();
  region.A.resize(n + 2, 3);
  region.b.resize(n + 2);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = hull[i].head<2>();
    const Eigen::Vector2d q = hull[(i + 1) % n].head<2>();
    const Eigen::Vector2d edge = q - p;
    // Outward normal of a CCW polygon edge is (edge.y, -edge.x).
    const Eigen::Vector2d out = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
    region.A.row(i) << out.x(), out.y(), 0.0;
    region.b(i) = out.dot(p);
    // Put the vertex exactly on the fitted plane.
    hull[i].z() = plane.x() * hull[i].x() + plane.y() * hull[i].y() + plane.z();
  }
  // Plane slab along the unit normal: |n . f - d| <= tol.
  const double d = region.normal_world.dot(Eigen::Vector3d(0.0, 0.0, plane.z()));
  region.A.row(n) = region.normal_world.transpose();
  region.b(n) = d + plane_tolerance_m;
  region.A.row(n + 1) = -region.normal_world.transpose();
  region.b(n + 1) = -d + plane_tolerance_m;
  region.vertices_world_m = hull;
  // Area on the plane = projected area / cos(slope).
  double twice_area = 0.0;
  for (size_t i = 0; i < n; ++i) twice_area += Cross2(hull[i].head<2>(), hull[(i + 1) % n].head<2>());
  region.area_m2 = 0.5 * twice_area / region.normal_world.z();
  return region;
}

double RegionViolation(const ConvexRegion& region, const Eigen::Vector3d& point_world_m) {
  if (region.b.size() == 0) return std::numeric_limits<double>::infinity();
  return (region.A * point_world_m - region.b).maxCoeff();
}

Eigen::Vector2d ClosestPointOnSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return a + t * d;
}

Eigen::Vector2d ClosestBoundaryPoint(const std::vector<Eigen::Vector2d>& polygon_m, const Eigen::Vector2d& xy_m) {
  MFP_CHECK(!polygon_m.empty());
  Eigen::Vector2d best = polygon_m.front();
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < polygon_m.size(); ++k) {
    const Eigen::Vector2d q = ClosestPointOnSegment(xy_m, polygon_m[k], polygon_m[(k + 1) % polygon_m.size()]);
    if ((q - xy_m).norm() < best_d) {
      best_d = (q - xy_m).norm();
      best = q;
    }
  }
  return best;
}

double PlanDistanceToRegion(const ConvexRegion& region, const Eigen::Vector2d& xy_m) {
  const auto& v = region.vertices_world_m;
  bool inside = v.size() >= 3;
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < v.size(); ++k) {
    const Eigen::Vector2d a = v[k].head<2>(), b = v[(k + 1) % v.size()].head<2>();
    const Eigen::Vector2d e = b - a;
    if (e.x() * (xy_m - a).y() - e.y() * (xy_m - a).x() < -1e-12) inside = false;
    const double t = e.squaredNorm() > 0 ? std::clamp((xy_m - a).dot(e) / e.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * e - xy_m).norm());
  }
  return inside ? 0.0 : best;
}

bool RegionContains(const ConvexRegion& region, const Eigen::Vector3d& point_world_m,
                    double tolerance_m) {
  return RegionViolation(region, point_world_m) <= tolerance_m;
}

int FindRegionBelow(const std::vector<ConvexRegion>& regions, double x_m, double y_m,
                    double tolerance_m) {
  int best = -1;
  double best_height = -std::numeric_limits<double>::infinity();
  for (size_t r = 0; r < regions.size(); ++r) {
    const ConvexRegion& region = regions[r];
    const Eigen::Index edges = region.A.rows() - 2;
    bool inside = edges > 0;
    for (Eigen::Index j = 0; j < edges && inside; ++j) {
      inside = region.A(j, 0) * x_m + region.A(j, 1) * y_m <= region.b(j) + tolerance_m;
    }
    // Where regions overlap in plan view, the highest surface is the one stood on.
    if (inside) {
      const double h = region.HeightAt(x_m, y_m);
      if (h > best_height) {
        best_height = h;
        best = static_cast<int>(r);
      }
    }
  }
  return best;
}

}  // namespace mfp
