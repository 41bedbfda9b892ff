#pragma once
// The union of convex polygons inset by a margin, as few convex pieces: the footholds of
// a surface made of several coplanar faces (a walkway of rotated boxes, a floor of
// tiles), where insetting each face by itself would leave a strip twice the margin wide
// along every seam. Used by TopFaceRegions.
#include <Eigen/Core>
#include <vector>

namespace mfp {

using Polygon2d = std::vector<Eigen::Vector2d>;  // convex, counter-clockwise

// A convex polygon grown by margin_m: every edge moved outward by margin_m, and every
// corner turning more than 45 degrees bevelled by edges tangent to the circle of radius
// margin_m about it, so the result contains every point within margin_m of the polygon
// and reaches at most margin_m / cos(22.5 deg) from it (a plain mitre reaches 1.41
// margin_m at a right angle, arbitrarily far at a sharp corner). Counter-clockwise.
Polygon2d GrowConvexPolygon(const Polygon2d& polygon, double margin_m);

// The intersection of two convex polygons (empty when they do not overlap).
Polygon2d ConvexIntersection(const Polygon2d& a, const Polygon2d& b);

// The smallest width of a convex polygon: the least distance between two parallel lines
// enclosing it [m].
double ConvexWidth(const Polygon2d& polygon);

struct UnionInsetOptions {
  double inset_m = 0.0;  // least distance of a kept point from the union's outside [m]
  // Gaps between faces narrower than this are seams, not gaps: faces that abut up to
  // rounding (or a user's few-decimal coordinates) make one surface [m].
  double seam_gap_m = 1e-4;
  double min_piece_area_m2 = 1e-6;  // smaller pieces are dropped [m^2]
  // Pieces smaller than this that touch a larger piece are dropped: slivers beside a
  // seam that would cost a region each for little room [m^2].
  double min_useful_area_m2 = 1e-3;
};

// The points of the union of `faces` at distance >= inset_m from every point outside the
// union (gaps narrower than seam_gap_m excepted) and >= inset_m from every polygon of
// `obstacles`, as convex counter-clockwise pieces. Sound: a kept point's disk of radius
// inset_m lies in the union, clear of the obstacles; bevelled corners (GrowConvexPolygon)
// and dropped slivers (min_piece_area_m2, min_useful_area_m2) give up a little more.
// Pieces may overlap: a piece is merged with its neighbours into their hull wherever the
// hull holds only kept points (MergeConvexPieces).
std::vector<Polygon2d> InsetUnionOfConvexPolygons(const std::vector<Polygon2d>& faces,
                                                  const std::vector<Polygon2d>& obstacles,
                                                  const UnionInsetOptions& options);

// Fewer, larger convex pieces covering `pieces`: largest first, a piece is replaced by
// its convex hull with a neighbour while that hull lies inside the union of `within`
// (disjoint convex polygons; up to a sliver of width about 1e-7 m), and pieces the hull
// then contains are dropped. The result may overlap; every point of it is in `within`.
std::vector<Polygon2d> MergeConvexPieces(std::vector<Polygon2d> pieces, const std::vector<Polygon2d>& within);

}  // namespace mfp
