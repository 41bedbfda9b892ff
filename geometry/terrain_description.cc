#include "geometry/terrain_description.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "base/check.h"
#include "geometry/convex_hull_2d.h"
#include "geometry/internal/convex_polygon_difference.h"
#include "geometry/internal/union_inset.h"

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

// The top face of a box: the face whose outward normal points most upward.
struct Face {
  Eigen::Vector3d point_world_m;   // the face's centre
  Eigen::Vector3d normal_world;    // upward unit normal
  Eigen::Vector3d axis_u, axis_v;  // unit edge directions of the face (world)
  double half_u_m = 0.0, half_v_m = 0.0;
  std::vector<Eigen::Vector2d> xy; // the face inset by a margin seen from above, counter-clockwise
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

// The top face of a box, or false when it is steeper than max_slope_rad.
bool BoxTopFace(const TerrainBox& box, double max_slope_rad, Face* face) {
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
  if (slope > max_slope_rad) return false;
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  face->normal_world = sign * R.col(axis);
  face->point_world_m = box.center_world_m + R.col(axis) * (sign * 0.5 * box.size_m(axis));
  face->axis_u = R.col(u);
  face->axis_v = R.col(v);
  face->half_u_m = 0.5 * box.size_m(u);
  face->half_v_m = 0.5 * box.size_m(v);
  return true;
}

// The face's corners inset by inset_m, in the world frame, counter-clockwise seen from
// above; empty when nothing is left.
std::vector<Eigen::Vector3d> FaceCorners(const Face& face, double inset_m) {
  const double half_u = face.half_u_m - inset_m;
  const double half_v = face.half_v_m - inset_m;
  if (half_u <= 1e-6 || half_v <= 1e-6) return {};
  std::vector<Eigen::Vector3d> corners;
  const std::array<std::array<double, 2>, 4> signs = {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
  for (const auto& c : signs) {
    corners.push_back(face.point_world_m + face.axis_u * (c[0] * half_u) + face.axis_v * (c[1] * half_v));
  }
  return corners;
}

void AppendRegions(const Face& face, const std::vector<std::vector<Eigen::Vector2d>>& pieces_xy,
                   std::vector<ConvexRegion>* regions) {
  for (const auto& piece : pieces_xy) {
    std::vector<Eigen::Vector3d> vertices;
    for (const Eigen::Vector2d& p : piece) vertices.emplace_back(p.x(), p.y(), PlaneHeight(face, p));
    regions->push_back(MakeRegionFromPolygon(static_cast<int>(regions->size()), vertices, 0.0));
  }
}

// A face with no coplanar neighbour: inset by itself, less what other boxes cover.
std::vector<std::vector<Eigen::Vector2d>> LoneFacePieces(const TerrainDescription& terrain, size_t i, Face face,
                                                         const std::vector<std::vector<Eigen::Vector2d>>& footprints,
                                                         double inset_m) {
  for (const Eigen::Vector3d& c : FaceCorners(face, inset_m)) face.xy.push_back(c.head<2>());
  if (face.xy.empty()) return {};
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
  return pieces;
}

// Faces on one plane that touch make one surface: the union of their faces inset once, in
// coordinates along the plane (true distances on a tilted plane), less what other boxes
// cover, as few convex pieces.
std::vector<std::vector<Eigen::Vector2d>> CoplanarFacesPieces(const TerrainDescription& terrain,
                                                              const std::vector<size_t>& members,
                                                              const std::vector<Face>& faces,
                                                              const std::vector<std::vector<Eigen::Vector2d>>& footprints,
                                                              double inset_m) {
  const Face& plane = faces[members.front()];
  const Eigen::Vector3d& n = plane.normal_world;
  const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - n.x() * n).normalized();
  const Eigen::Vector3d e2 = n.cross(e1);
  const Eigen::Vector3d& o = plane.point_world_m;
  auto along = [&](const Eigen::Vector3d& p) { return Eigen::Vector2d((p - o).dot(e1), (p - o).dot(e2)); };
  std::vector<Polygon2d> members_uv;
  std::vector<Eigen::Vector2d> outline_xy;  // the members' corners seen from above
  for (size_t m : members) {
    Polygon2d uv;
    for (const Eigen::Vector3d& c : FaceCorners(faces[m], 0.0)) {
      uv.push_back(along(c));
      outline_xy.push_back(c.head<2>());
    }
    members_uv.push_back(std::move(uv));
  }
  std::vector<Polygon2d> covers_uv;
  for (size_t j = 0; j < terrain.boxes.size(); ++j) {
    if (std::find(members.begin(), members.end(), j) != members.end()) continue;
    if (!BoundsOverlap(outline_xy, footprints[j], inset_m)) continue;
    const std::vector<Eigen::Vector2d> cover = PartAbove(terrain.boxes[j], plane);
    if (cover.empty() || !BoundsOverlap(outline_xy, cover, inset_m)) continue;
    Polygon2d uv;
    for (const Eigen::Vector2d& p : cover) uv.push_back(along(Eigen::Vector3d(p.x(), p.y(), PlaneHeight(plane, p))));
    covers_uv.push_back(std::move(uv));
  }
  UnionInsetOptions options;
  options.inset_m = inset_m;
  options.min_piece_area_m2 = kMinPieceAreaM2;
  std::vector<std::vector<Eigen::Vector2d>> pieces_xy;
  for (const Polygon2d& piece : InsetUnionOfConvexPolygons(members_uv, covers_uv, options)) {
    std::vector<Eigen::Vector2d> xy;
    for (const Eigen::Vector2d& p : piece) xy.push_back((o + p.x() * e1 + p.y() * e2).head<2>());
    pieces_xy.push_back(std::move(xy));
  }
  return pieces_xy;
}

// Whether two faces lie on one plane (within kCoverHeightM) and touch or overlap (up to
// the seam gap of UnionInsetOptions).
bool FacesJoin(const Face& a, const Face& b) {
  if (a.normal_world.dot(b.normal_world) < 1.0 - 1e-12) return false;
  if (std::abs(a.normal_world.dot(b.point_world_m - a.point_world_m)) > kCoverHeightM) return false;
  Polygon2d pa, pb;
  for (const Eigen::Vector3d& c : FaceCorners(a, 0.0)) pa.push_back(c.head<2>());
  for (const Eigen::Vector3d& c : FaceCorners(b, 0.0)) pb.push_back(c.head<2>());
  if (pa.empty() || pb.empty() || !BoundsOverlap(pa, pb, 1e-3)) return false;
  return !ConvexIntersection(GrowConvexPolygon(pa, UnionInsetOptions{}.seam_gap_m), ConvexHull2d(pb)).empty();
}

// Groups of faces that join (FacesJoin), each listed in box order, the groups in the
// order of their first box.
std::vector<std::vector<size_t>> JoinedFaces(const std::vector<Face>& faces, const std::vector<bool>& has_face) {
  std::vector<size_t> root(faces.size());
  for (size_t i = 0; i < root.size(); ++i) root[i] = i;
  auto find = [&](size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (size_t i = 0; i < faces.size(); ++i) {
    for (size_t j = i + 1; j < faces.size(); ++j) {
      if (!has_face[i] || !has_face[j] || find(i) == find(j) || !FacesJoin(faces[i], faces[j])) continue;
      root[std::max(find(i), find(j))] = std::min(find(i), find(j));
    }
  }
  std::vector<std::vector<size_t>> groups;
  std::vector<int> group_of(faces.size(), -1);
  for (size_t i = 0; i < faces.size(); ++i) {
    if (!has_face[i]) continue;
    const size_t r = find(i);
    if (group_of[r] < 0) {
      group_of[r] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<size_t>(group_of[r])].push_back(i);
  }
  return groups;
}

void CheckBoxes(const TerrainDescription& terrain) {
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
}

}  // namespace

std::vector<ConvexRegion> TopFaceRegions(const TerrainDescription& terrain, double inset_m,
                                         double max_slope_rad) {
  CheckBoxes(terrain);
  // Each box's corners seen from above, to pass over boxes far from a face quickly.
  std::vector<std::vector<Eigen::Vector2d>> footprints;
  for (const TerrainBox& box : terrain.boxes) {
    std::vector<Eigen::Vector2d> xy;
    for (const Eigen::Vector3d& c : BoxCorners(box)) xy.push_back(c.head<2>());
    footprints.push_back(std::move(xy));
  }
  std::vector<Face> faces(terrain.boxes.size());
  std::vector<bool> has_face(terrain.boxes.size());
  for (size_t i = 0; i < terrain.boxes.size(); ++i) has_face[i] = BoxTopFace(terrain.boxes[i], max_slope_rad, &faces[i]);
  std::vector<ConvexRegion> regions;
  for (const std::vector<size_t>& group : JoinedFaces(faces, has_face)) {
    const Face& first = faces[group.front()];
    AppendRegions(first,
                  group.size() == 1 ? LoneFacePieces(terrain, group.front(), first, footprints, inset_m)
                                    : CoplanarFacesPieces(terrain, group, faces, footprints, inset_m),
                  &regions);
  }
  return regions;
}

}  // namespace mfp
