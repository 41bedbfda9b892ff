#include "geometry/internal/union_inset.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "geometry/convex_hull_2d.h"
#include "geometry/internal/convex_polygon_difference.h"

namespace mfp {
namespace {

// Largest turn between two edges of a grown corner: bevels keep the corner within
// margin / cos(kMaxTurnRad / 2) of the polygon [rad].
constexpr double kMaxTurnRad = M_PI / 4;
// Two pieces merge when their hull exceeds their union by less than a sliver this wide
// along the hull's perimeter [m].
constexpr double kMergeSliverM = 1e-7;

Eigen::Vector2d OutwardNormal(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  return Eigen::Vector2d(e.y(), -e.x()).normalized();
}

double Perimeter(const Polygon2d& p) {
  double length = 0.0;
  for (size_t i = 0; i < p.size(); ++i) length += (p[(i + 1) % p.size()] - p[i]).norm();
  return length;
}

bool BoundsTouch(const Polygon2d& a, const Polygon2d& b, double grow_m) {
  Eigen::Vector2d alo = a[0], ahi = a[0], blo = b[0], bhi = b[0];
  for (const auto& p : a) alo = alo.cwiseMin(p), ahi = ahi.cwiseMax(p);
  for (const auto& p : b) blo = blo.cwiseMin(p), bhi = bhi.cwiseMax(p);
  return (alo.array() <= bhi.array() + grow_m).all() && (blo.array() <= ahi.array() + grow_m).all();
}

// Every piece of `pieces` less `cut`, pieces below min_area_m2 dropped.
std::vector<Polygon2d> Subtract(const std::vector<Polygon2d>& pieces, const Polygon2d& cut, double min_area_m2) {
  std::vector<Polygon2d> out;
  for (const Polygon2d& piece : pieces) {
    if (!BoundsTouch(piece, cut, 0.0)) {
      out.push_back(piece);
      continue;
    }
    for (Polygon2d& kept : ConvexPolygonMinus(piece, cut, 0.0, min_area_m2)) out.push_back(std::move(kept));
  }
  return out;
}

// The parts of the neighbourhood of faces[i] (within inset_m and a little more) that no
// face covers, as convex pieces; pieces narrower than seam_gap_m are seams and dropped.
std::vector<Polygon2d> GapsAround(const std::vector<Polygon2d>& faces, size_t i, const UnionInsetOptions& options) {
  const Polygon2d around = GrowConvexPolygon(faces[i], options.inset_m + options.seam_gap_m);
  std::vector<Polygon2d> gaps = {around};
  for (size_t j = 0; j < faces.size() && !gaps.empty(); ++j) {
    if (BoundsTouch(around, faces[j], 0.0)) gaps = Subtract(gaps, faces[j], 0.0);
  }
  std::vector<Polygon2d> wide;
  for (Polygon2d& gap : gaps) {
    if (ConvexWidth(gap) >= options.seam_gap_m) wide.push_back(std::move(gap));
  }
  return wide;
}

// Small pieces beside a larger one (slivers where a grown gap's tip cut a seam) add
// little room and a region each: dropped. A small piece alone is a foothold and stays.
std::vector<Polygon2d> DropSmallSidePieces(std::vector<Polygon2d> out, const UnionInsetOptions& options) {
  std::vector<bool> drop(out.size(), false);
  for (size_t i = 0; i < out.size(); ++i) {
    const double area = std::abs(PolygonArea2d(out[i]));
    if (area >= options.min_useful_area_m2) continue;
    const Polygon2d around = GrowConvexPolygon(out[i], options.seam_gap_m);
    for (size_t j = 0; j < out.size() && !drop[i]; ++j) {
      drop[i] = j != i && !drop[j] && std::abs(PolygonArea2d(out[j])) > area && BoundsTouch(around, out[j], 0.0) &&
                !ConvexIntersection(around, out[j]).empty();
    }
  }
  std::vector<Polygon2d> useful;
  for (size_t i = 0; i < out.size(); ++i) {
    if (!drop[i]) useful.push_back(std::move(out[i]));
  }
  return useful;
}

}  // namespace

Polygon2d GrowConvexPolygon(const Polygon2d& polygon, double margin_m) {
  MFP_CHECK(margin_m >= 0.0);
  const Polygon2d p = ConvexHull2d(polygon);
  if (margin_m == 0.0 || p.size() < 3) return p;
  Polygon2d out;
  const size_t m = p.size();
  for (size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d& corner = p[i];
    const Eigen::Vector2d n_in = OutwardNormal(p[(i + m - 1) % m], corner);
    const Eigen::Vector2d n_out = OutwardNormal(corner, p[(i + 1) % m]);
    const double turn = std::atan2(n_in.x() * n_out.y() - n_in.y() * n_out.x(), n_in.dot(n_out));
    const int steps = std::max(1, static_cast<int>(std::ceil(turn / kMaxTurnRad - 1e-9)));
    const double a0 = std::atan2(n_in.y(), n_in.x());
    for (int k = 0; k < steps; ++k) {  // the tangent lines at normals a0 + k turn / steps meet here
      const Eigen::Vector2d m0(std::cos(a0 + turn * k / steps), std::sin(a0 + turn * k / steps));
      const Eigen::Vector2d m1(std::cos(a0 + turn * (k + 1) / steps), std::sin(a0 + turn * (k + 1) / steps));
      out.push_back(corner + margin_m * (m0 + m1) / (1.0 + m0.dot(m1)));
    }
  }
  return ConvexHull2d(out);
}

Polygon2d ConvexIntersection(const Polygon2d& a, const Polygon2d& b) {
  Polygon2d out = a;
  for (size_t i = 0; i < b.size() && out.size() >= 3; ++i) {
    const Eigen::Vector2d& p = b[i];
    const Eigen::Vector2d& q = b[(i + 1) % b.size()];
    if ((q - p).norm() <= 1e-12) continue;
    const Eigen::Vector2d n = OutwardNormal(p, q);
    out = KeepBelowLine(out, n, n.dot(p));
  }
  if (out.size() < 3) return {};
  return out;
}

double ConvexWidth(const Polygon2d& polygon) {
  double width = polygon.size() < 3 ? 0.0 : INFINITY;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    if ((q - p).norm() <= 1e-12) continue;
    const Eigen::Vector2d n = OutwardNormal(p, q);
    double far = 0.0;
    for (const Eigen::Vector2d& v : polygon) far = std::max(far, n.dot(p - v));
    width = std::min(width, far);
  }
  return width;
}

namespace {

struct Bounds {
  Eigen::Vector2d lo, hi;
  explicit Bounds(const Polygon2d& p) : lo(p[0]), hi(p[0]) {
    for (const Eigen::Vector2d& v : p) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  }
  bool Touch(const Bounds& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

bool ConvexContains(const Polygon2d& p, const Eigen::Vector2d& q, double tol) {
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d e = p[(i + 1) % p.size()] - p[i];
    if (e.x() * (q - p[i]).y() - e.y() * (q - p[i]).x() < -tol * e.norm()) return false;
  }
  return true;
}

}  // namespace

std::vector<Polygon2d> MergeConvexPieces(std::vector<Polygon2d> pieces, const std::vector<Polygon2d>& within) {
  std::vector<Bounds> within_bounds;
  for (const Polygon2d& w : within) within_bounds.emplace_back(w);
  // Whether a polygon lies in the union of `within` (whose pieces are disjoint): points
  // along its edges first (most hulls that leave the union fail there), then its area.
  auto inside_within = [&](const Polygon2d& p) {
    const Bounds b(p);
    std::vector<size_t> near;
    for (size_t k = 0; k < within.size(); ++k) {
      if (within_bounds[k].Touch(b)) near.push_back(k);
    }
    for (size_t i = 0; i < p.size(); ++i) {
      for (double t : {0.25, 0.5, 0.75}) {
        const Eigen::Vector2d q = p[i] + t * (p[(i + 1) % p.size()] - p[i]);
        if (std::none_of(near.begin(), near.end(), [&](size_t k) { return ConvexContains(within[k], q, kMergeSliverM); })) {
          return false;
        }
      }
    }
    double a = 0.0;
    for (size_t k : near) a += std::abs(PolygonArea2d(ConvexIntersection(p, within[k])));
    return PolygonArea2d(p) - a <= kMergeSliverM * Perimeter(p);
  };
  // The hull of pieces i and j lies in `within` when what it adds to piece i does (piece
  // i does): checked on the pieces of hull less piece i, small where piece j is.
  auto hull_inside = [&](const Polygon2d& hull, const Polygon2d& piece) {
    for (const Polygon2d& added : ConvexPolygonMinus(hull, piece, 0.0, 0.0)) {
      if (added.size() >= 3 && !inside_within(added)) return false;
    }
    return true;
  };
  auto covers = [](const Polygon2d& big, const Polygon2d& small) {  // small lies in big
    return std::all_of(small.begin(), small.end(), [&](const Eigen::Vector2d& v) { return ConvexContains(big, v, kMergeSliverM); });
  };
  std::stable_sort(pieces.begin(), pieces.end(), [](const Polygon2d& a, const Polygon2d& b) {
    return std::abs(PolygonArea2d(a)) > std::abs(PolygonArea2d(b));
  });
  for (size_t i = 0; i < pieces.size(); ++i) {
    for (size_t j = 0; j < pieces.size(); ++j) {
      if (j == i || !BoundsTouch(pieces[i], pieces[j], kMergeSliverM)) continue;
      Polygon2d points = pieces[i];
      points.insert(points.end(), pieces[j].begin(), pieces[j].end());
      Polygon2d hull = ConvexHull2d(points);
      if (!hull_inside(hull, pieces[i])) continue;
      // The hull replaces piece i and every piece it contains; look again from the start.
      std::vector<Polygon2d> kept;
      size_t new_i = 0;
      for (size_t k = 0; k < pieces.size(); ++k) {
        if (k == i) {
          new_i = kept.size();
          kept.push_back(hull);
        } else if (!BoundsTouch(hull, pieces[k], 0.0) || !covers(hull, pieces[k])) {
          kept.push_back(std::move(pieces[k]));
        }
      }
      pieces = std::move(kept);
      i = new_i;
      j = static_cast<size_t>(-1);
    }
  }
  return pieces;
}

std::vector<Polygon2d> InsetUnionOfConvexPolygons(const std::vector<Polygon2d>& faces,
                                                  const std::vector<Polygon2d>& obstacles,
                                                  const UnionInsetOptions& options) {
  MFP_CHECK(options.inset_m >= 0.0 && options.seam_gap_m >= 0.0);
  std::vector<Polygon2d> hulls;
  for (const Polygon2d& f : faces) {
    Polygon2d h = ConvexHull2d(f);
    if (h.size() >= 3) hulls.push_back(std::move(h));
  }
  std::vector<Polygon2d> grown_obstacles;
  for (const Polygon2d& o : obstacles) {
    Polygon2d g = GrowConvexPolygon(o, options.inset_m);
    if (g.size() >= 3) grown_obstacles.push_back(std::move(g));
  }
  // A point of face i is within inset_m of the union's outside exactly when it is within
  // inset_m of an uncovered part of face i's neighbourhood: cut those parts, grown.
  // Each face less the faces before it: disjoint pieces, so that MergeConvexPieces can
  // measure what of a hull the kept points cover.
  std::vector<Polygon2d> kept, merged;
  for (size_t i = 0; i < hulls.size(); ++i) {
    std::vector<Polygon2d> pieces = {hulls[i]};
    for (size_t j = 0; j < i && !pieces.empty(); ++j) {
      if (BoundsTouch(hulls[i], hulls[j], 0.0)) pieces = Subtract(pieces, hulls[j], options.min_piece_area_m2);
    }
    for (const Polygon2d& gap : GapsAround(hulls, i, options)) {
      pieces = Subtract(pieces, GrowConvexPolygon(gap, options.inset_m), options.min_piece_area_m2);
    }
    for (const Polygon2d& cut : grown_obstacles) pieces = Subtract(pieces, cut, options.min_piece_area_m2);
    kept.insert(kept.end(), pieces.begin(), pieces.end());
    for (Polygon2d& p : MergeConvexPieces(pieces, pieces)) merged.push_back(std::move(p));  // few, then all
  }
  return DropSmallSidePieces(MergeConvexPieces(std::move(merged), kept), options);
}

}  // namespace mfp
