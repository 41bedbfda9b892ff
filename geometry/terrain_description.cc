#include "geometry/terrain_description.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "base/check.h"
#include "geometry/convex_hull_2d.h"
#include "geometry/internal/convex_polygon_difference.h"

namespace mfp {

Eigen::Matrix3d BoxRotation(const TerrainBox& box) {
  return (Eigen::AngleAxisd(box.rpy_rad.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(box.rpy_rad.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(box.rpy_rad.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

bool RayBoxInterval(const TerrainBox& box, const Eigen::Matrix3d& R, const Eigen::Vector3d& o,
                    const Eigen::Vector3d& d, double parallel_tol, double* t_in, double* t_out) {
  const Eigen::Vector3d lo = R.transpose() * (o - box.center_world_m);
  const Eigen::Vector3d ld = R.transpose() * d;
  *t_in = -std::numeric_limits<double>::infinity();
  *t_out = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double h = 0.5 * box.size_m(a);
    if (std::abs(ld(a)) < parallel_tol) {
      if (std::abs(lo(a)) > h) return false;
      continue;
    }
    double t0 = (-h - lo(a)) / ld(a), t1 = (h - lo(a)) / ld(a);
    if (t0 > t1) std::swap(t0, t1);
    *t_in = std::max(*t_in, t0);
    *t_out = std::min(*t_out, t1);
  }
  return *t_in <= *t_out;
}

std::vector<Eigen::Vector3d> BoxCorners(const TerrainBox& box) {
  const Eigen::Matrix3d R = BoxRotation(box);
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    corners.push_back(box.center_world_m + R * (0.5 * sign.cwiseProduct(box.size_m)));
  }
  return corners;
}

namespace {

// Heights closer than this to a face count as on it, not above it (abutting boxes of the
// same height do not cover each other) [m].
constexpr double kCoverHeightM = 1e-5;
// Pieces of a face smaller than this are dropped (slivers left by cuts) [m^2].
constexpr double kMinPieceAreaM2 = 1e-6;

struct Face {
  Eigen::Vector3d point_world_m;   // a point of the face's plane
  Eigen::Vector3d normal_world;    // upward unit normal
  std::vector<Eigen::Vector2d> xy; // the inset face seen from above, counter-clockwise
};

double PlaneHeight(const Face& f, const Eigen::Vector2d& xy) {
  const Eigen::Vector3d& n = f.normal_world;
  return f.point_world_m.z() -
         (n.x() * (xy.x() - f.point_world_m.x()) + n.y() * (xy.y() - f.point_world_m.y())) / n.z();
}

// The part of a box that lies above the face's plane, seen from above (its convex hull;
// empty when the box reaches no higher than the plane). Convex: the projection of a box
// cut by a half-space.
std::vector<Eigen::Vector2d> PartAbove(const TerrainBox& box, const Face& face) {
  const std::vector<Eigen::Vector3d> corners = BoxCorners(box);
  std::array<double, 8> s{};
  for (int i = 0; i < 8; ++i) s[i] = face.normal_world.dot(corners[i] - face.point_world_m) - kCoverHeightM;
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 8; ++i) {
    if (s[i] > 0.0) points.push_back(corners[i].head<2>());
    for (int bit : {1, 2, 4}) {  // the box's edges: corners differing in one sign bit
      const int j = i | bit;
      if (j == i || (s[i] > 0.0) == (s[j] > 0.0)) continue;
      points.push_back((corners[i] + (corners[j] - corners[i]) * (s[i] / (s[i] - s[j]))).head<2>());
    }
  }
  if (points.size() < 3) return {};
  std::vector<Eigen::Vector2d> hull = ConvexHull2d(points);
  if (hull.size() < 3) return {};
  return hull;
}

bool BoundsOverlap(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b, double grow_m) {
  Eigen::Vector2d alo = a[0], ahi = a[0], blo = b[0], bhi = b[0];
  for (const auto& p : a) alo = alo.cwiseMin(p), ahi = ahi.cwiseMax(p);
  for (const auto& p : b) blo = blo.cwiseMin(p), bhi = bhi.cwiseMax(p);
  return (alo.array() <= bhi.array() + grow_m).all() && (blo.array() <= ahi.array() + grow_m).all();
}

}  // namespace

std::vector<ConvexRegion> TopFaceRegions(const TerrainDescription& terrain, double inset_m,
                                         double max_slope_rad) {
  std::vector<ConvexRegion> regions;
  for (size_t i = 0; i < terrain.boxes.size(); ++i) {
    const TerrainBox& box = terrain.boxes[i];
    const std::string name = "terrain box " + std::to_string(i) +
                             (box.name.empty() ? "" : " ('" + box.name + "')");
    if (!box.center_world_m.allFinite() || !box.size_m.allFinite() || !box.rpy_rad.allFinite()) {
      throw InputError(name + ": centre, size and rpy must be finite numbers");
    }
    if ((box.size_m.array() <= 0.0).any()) {
      throw InputError(name + ": every size must be > 0 m");
    }
  }
  // Each box's corners seen from above, to pass over boxes far from a face quickly.
  std::vector<std::vector<Eigen::Vector2d>> footprints;
  for (const TerrainBox& box : terrain.boxes) {
    std::vector<Eigen::Vector2d> xy;
    for (const Eigen::Vector3d& c : BoxCorners(box)) xy.push_back(c.head<2>());
    footprints.push_back(std::move(xy));
  }
  for (size_t i = 0; i < terrain.boxes.size(); ++i) {
    const TerrainBox& box = terrain.boxes[i];
    const Eigen::Matrix3d R = BoxRotation(box);
    // Pick the box axis (with sign) most aligned with world up.
    int axis = 0;
    double best = -2.0;
    double sign = 1.0;
    for (int a = 0; a < 3; ++a) {
      for (double s : {1.0, -1.0}) {
        const double up = s * R(2, a);
        if (up > best) {
          best = up;
          axis = a;
          sign = s;
        }
      }
    }
    const double slope = std::acos(std::min(1.0, best));
    if (slope > max_slope_rad) continue;
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    const double half_u = 0.5 * box.size_m(u) - inset_m;
    const double half_v = 0.5 * box.size_m(v) - inset_m;
    if (half_u <= 1e-6 || half_v <= 1e-6) continue;
    Face face;
    face.normal_world = sign * R.col(axis);
    face.point_world_m = box.center_world_m + R.col(axis) * (sign * 0.5 * box.size_m(axis));
    const std::array<std::array<double, 2>, 4> corners = {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
    for (const auto& c : corners) {
      face.xy.push_back((face.point_world_m + R.col(u) * (c[0] * half_u) + R.col(v) * (c[1] * half_v)).head<2>());
    }
    if (PolygonArea2d(face.xy) < 0.0) std::reverse(face.xy.begin(), face.xy.end());
    // Cut away what other boxes cover: where a box rises above this face, a foot there
    // would be inside that box (boxes may overlap, or stand on a slab). The cut grows by
    // the inset, so a foot keeps the same distance from a covering box's side as from
    // the face's own edge.
    std::vector<std::vector<Eigen::Vector2d>> pieces = {face.xy};
    for (size_t j = 0; j < terrain.boxes.size() && !pieces.empty(); ++j) {
      if (j == i || !BoundsOverlap(face.xy, footprints[j], inset_m)) continue;
      const std::vector<Eigen::Vector2d> cover = PartAbove(terrain.boxes[j], face);
      if (cover.empty() || !BoundsOverlap(face.xy, cover, inset_m)) continue;
      std::vector<std::vector<Eigen::Vector2d>> next;
      for (const auto& piece : pieces) {
        for (auto& kept : ConvexPolygonMinus(piece, cover, inset_m, kMinPieceAreaM2)) next.push_back(std::move(kept));
      }
      pieces = std::move(next);
    }
    for (const auto& piece : pieces) {
      std::vector<Eigen::Vector3d> vertices;
      for (const Eigen::Vector2d& p : piece) vertices.emplace_back(p.x(), p.y(), PlaneHeight(face, p));
      regions.push_back(MakeRegionFromPolygon(static_cast<int>(regions.size()), vertices, 0.0));
    }
  }
  return regions;
}

}  // namespace mfp
