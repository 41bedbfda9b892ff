#pragma once
// Convex obstacle-free regions of the plane, grown about a seed shape in the manner of
// IRIS (Deits and Tedrake): each obstacle that still meets the region is cut off by one
// separating line, the obstacles nearest the seed first, so the region keeps the seed and
// as much room around it as single lines allow. Sound by construction: no obstacle's
// interior meets the region (an obstacle is either cut off by its own line or meets the
// region in no area). Plain Eigen; no I/O.
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace mfp {

// { x : A x <= b }, rows of A unit normals, with its polygon (counter-clockwise).
struct FreeRegion2d {
  Eigen::Matrix<double, Eigen::Dynamic, 2> A;
  Eigen::VectorXd b;
  std::vector<Eigen::Vector2d> polygon;
};

// The free region about `seed` (a convex counter-clockwise polygon: the shape the region
// must hold) among convex counter-clockwise `obstacles`, within the box [lo, hi].
// nullopt when the seed overlaps an obstacle in more than touching (no line separates
// them) or leaves the box. Each obstacle's line is the one among the two polygons' edge
// normals (and the direction between their centres) that leaves the widest gap, placed
// against the obstacle, so the region reaches up to it.
std::optional<FreeRegion2d> GrowFreeRegion(const std::vector<Eigen::Vector2d>& seed,
                                           const std::vector<std::vector<Eigen::Vector2d>>& obstacles,
                                           const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

// Largest excess a . p - b over the region's rows and the points (<= 0: all inside).
double RegionExcess(const FreeRegion2d& region, const std::vector<Eigen::Vector2d>& points);

}  // namespace mfp
