#pragma once
// A convex polygon minus a convex polygon grown by a margin, as disjoint convex pieces.
// Used to cut the parts of a box's top face that other boxes cover (TopFaceRegions).
#include <Eigen/Core>
#include <vector>

#include "geometry/half_plane_clip.h"

namespace mfp {

// The points of `polygon` (counter-clockwise) outside `cut` (counter-clockwise, at least
// 3 vertices) grown by margin_m: each edge of `cut` moved outward by margin_m, so the
// removed set contains every point within margin_m of `cut` (mitred corners remove a
// little more, on the safe side). Pieces are convex, counter-clockwise and disjoint but
// for shared edges; pieces with an area below min_area_m2 are dropped. A cut that only
// touches the polygon (overlap of no area, up to rounding) leaves it whole, one piece.
std::vector<std::vector<Eigen::Vector2d>> ConvexPolygonMinus(const std::vector<Eigen::Vector2d>& polygon,
                                                             const std::vector<Eigen::Vector2d>& cut,
                                                             double margin_m, double min_area_m2);

// Area of a simple polygon, positive when counter-clockwise [m^2].
double PolygonArea2d(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace mfp
