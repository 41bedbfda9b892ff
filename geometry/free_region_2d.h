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

// GrowFreeRegion, telling also the region's bounds [*near_lo, *near_hi] when the first
// obstacle whose gap is at least near_gap comes up (the final region's when none does).
// An obstacle left out of `obstacles` would not have changed the region when its gap
// along one of the seed's edge normals is at least near_gap and its bounds lie strictly
// apart from those: the caller may grow among the near obstacles only and check.
std::optional<FreeRegion2d> GrowFreeRegionNear(const std::vector<Eigen::Vector2d>& seed,
                                               const std::vector<std::vector<Eigen::Vector2d>>& obstacles,
                                               const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double near_gap,
                                               Eigen::Vector2d* near_lo, Eigen::Vector2d* near_hi);

// GrowFreeRegionNear among the `count` obstacles from `obstacles` on (a caller's work
// space may hold more).
std::optional<FreeRegion2d> GrowFreeRegionNear(const std::vector<Eigen::Vector2d>& seed,
                                               const std::vector<Eigen::Vector2d>* obstacles, size_t count,
                                               const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double near_gap,
                                               Eigen::Vector2d* near_lo, Eigen::Vector2d* near_hi);

// Largest excess a . p - b over the region's rows and the points (<= 0: all inside).
double RegionExcess(const FreeRegion2d& region, const std::vector<Eigen::Vector2d>& points);

}  // namespace mfp
