#pragma once
// Distance between two convex polygons in the plane.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "geometry/convex_region.h"

namespace mfp {

// Whether a side of convex polygon `a` (counter-clockwise) has all of `b` on or beyond
// its line: then their interiors do not meet. Sides without length separate nothing.
template <typename P, typename Q>
bool SideOfFirstSeparates(const P& a, const Q& b) {
  const size_t n = a.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d edge = a[(i + 1) % n] - a[i];
    if (edge.squaredNorm() == 0.0) continue;
    bool separates = true;
    for (size_t j = 0; j < b.size() && separates; ++j) {
      const Eigen::Vector2d to = b[j] - a[i];
      separates = edge.x() * to.y() - edge.y() * to.x() <= 0.0;  // on the line or to the right
    }
    if (separates) return true;
  }
  return false;
}

// Distance between convex polygons p and q (vertices counter-clockwise, in any container
// of Eigen::Vector2d with size() and operator[]), 0 when their interiors meet. Apart (some
// side of either separates them), the nearest points are a vertex of one and a point on
// a side of the other.
template <typename P, typename Q>
double ConvexPolygonDistance(const P& p, const Q& q) {
  if (!SideOfFirstSeparates(p, q) && !SideOfFirstSeparates(q, p)) return 0.0;
  double d = INFINITY;
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d &a = p[i], &b = p[(i + 1) % p.size()];
    for (size_t j = 0; j < q.size(); ++j) {
      d = std::min({d, PointSegmentDistance(q[j], a, b), PointSegmentDistance(a, q[j], q[(j + 1) % q.size()])});
    }
  }
  return d;
}

// Whether ConvexPolygonDistance(p, q) < limit: the same answer (that distance is the least
// of the vertex-to-side distances it compares), given as soon as one of them is below the
// limit.
template <typename P, typename Q>
bool ConvexPolygonsNearer(const P& p, const Q& q, double limit) {
  if (!SideOfFirstSeparates(p, q) && !SideOfFirstSeparates(q, p)) return 0.0 < limit;
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d &a = p[i], &b = p[(i + 1) % p.size()];
    for (size_t j = 0; j < q.size(); ++j) {
      if (PointSegmentDistance(q[j], a, b) < limit || PointSegmentDistance(a, q[j], q[(j + 1) % q.size()]) < limit) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace mfp
