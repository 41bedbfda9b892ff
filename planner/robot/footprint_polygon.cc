#include "planner/robot/internal/footprint_polygon.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "geometry/half_plane_clip.h"

namespace mfp {
namespace {

// How far the foot reaches from p along the unit direction u, by steps of a tenth of a
// cell while the points stay in occupied cells [m].
double RayReach(const FootprintGrid& grid, const Eigen::Vector2d& p, const Eigen::Vector2d& u) {
  const double step = 0.1 * grid.cell_m();
  double t = 0.0;
  while (grid.OccupiedAt(p + (t + step) * u)) t += step;
  return t;
}

// Whether the square of half-side `half` centred at c (about the polygon's centre) meets the
// polygon: no separating axis among the faces' normals and the square's (exact for two
// convex polygons). When it does, *pull is the face whose line the square lies most beyond
// relative to its offset, among the faces that can be pulled in front of it and stay ahead of
// the centre: the one to pull in (-1 when there is none).
bool SquareMeets(const std::vector<ReachFace>& faces, const std::vector<Eigen::Vector2d>& corners,
                 const Eigen::Vector2d& c, double half, int* pull) {
  for (int axis = 0; axis < 2; ++axis) {
    double lo = corners.front()(axis), hi = lo;
    for (const Eigen::Vector2d& v : corners) {
      lo = std::min(lo, v(axis));
      hi = std::max(hi, v(axis));
    }
    if (c(axis) - half >= hi || c(axis) + half <= lo) return false;
  }
  double most = -1e300;
  for (size_t j = 0; j < faces.size(); ++j) {
    const Eigen::Vector2d& u = faces[j].normal;
    const double nearest = u.dot(c) - half * (std::abs(u.x()) + std::abs(u.y()));
    if (nearest >= faces[j].offset_m) return false;
    // Only a face that can be pulled in front of the square and stay ahead of the centre.
    if (nearest <= 0.0) continue;
    const double along = u.dot(c) / std::max(faces[j].offset_m, 1e-12);
    if (along > most) {
      most = along;
      *pull = static_cast<int>(j);
    }
  }
  return true;
}

}  // namespace

std::vector<Eigen::Vector2d> ReachFaceCorners(const std::vector<ReachFace>& faces) {
  double far = 0.0;
  for (const ReachFace& f : faces) far = std::max(far, std::abs(f.offset_m));
  far = 10.0 * std::max(far, 1e-6);
  std::vector<Eigen::Vector2d> poly = {{far, -far}, {far, far}, {-far, far}, {-far, -far}};
  for (const ReachFace& f : faces) poly = KeepBelowLine(poly, f.normal, f.offset_m);
  return poly;
}

std::vector<ReachFace> FootprintPolygon(const FootprintGrid& grid, const Eigen::Vector2d& centre_m, int faces) {
  MFP_CHECK(faces >= 3 && grid.OccupiedAt(centre_m));
  std::vector<ReachFace> out(static_cast<size_t>(faces));
  for (int j = 0; j < faces; ++j) {
    const double phi = 2.0 * M_PI * j / faces;
    out[j].normal = Eigen::Vector2d(std::cos(phi), std::sin(phi));
    out[j].offset_m = RayReach(grid, centre_m, out[j].normal);
  }
  // Empty cells that border occupied ones, and the grid's outer ring (empty), are the only
  // empty cells a convex polygon holding the occupied centre can meet first.
  std::vector<Eigen::Vector2d> empty;
  for (int iy = 0; iy < grid.ny(); ++iy) {
    for (int ix = 0; ix < grid.nx(); ++ix) {
      if (grid.Occupied(ix, iy)) continue;
      bool borders = ix == 0 || iy == 0 || ix + 1 == grid.nx() || iy + 1 == grid.ny();
      for (int dy = -1; dy <= 1 && !borders; ++dy) {
        for (int dx = -1; dx <= 1 && !borders; ++dx) borders = grid.Occupied(ix + dx, iy + dy);
      }
      if (borders) empty.push_back(grid.CellCentre(ix, iy) - centre_m);
    }
  }
  const double half = 0.5 * grid.cell_m();
  // Each pass pulls a face in for every conflicting cell; every pull clears its cell for
  // good (offsets only shrink), so the passes end.
  std::vector<Eigen::Vector2d> corners = ReachFaceCorners(out);
  for (bool conflict = true; conflict;) {
    conflict = false;
    for (const Eigen::Vector2d& c : empty) {
      int pull = -1;
      if (!SquareMeets(out, corners, c, half, &pull)) continue;
      if (pull < 0) {
        throw InputError(
            "footprint polygon: an unreachable cell touches the leg's nominal foot, so no polygon about it fits "
            "the leg's reachable footprint; check the leg's joint limits and nominal stance in the robot's "
            "URDF/YAML, or use reach_shape: hexadecagon");
      }
      ReachFace& f = out[static_cast<size_t>(pull)];
      f.offset_m = f.normal.dot(c) - half * (std::abs(f.normal.x()) + std::abs(f.normal.y())) - 1e-9;
      corners = ReachFaceCorners(out);
      conflict = true;
    }
  }
  return out;
}

}  // namespace mfp
