#pragma once
// The convex hull of points in the plane (Andrew's monotone chain), shared by the terrain
// pipeline (patch outlines) and the planner (hulls of region unions).
#include <Eigen/Core>
#include <vector>

namespace mfp {

// The hull's vertices counter-clockwise, without collinear or repeated points. Fewer
// than 3 distinct points come back sorted (by x, then y) and without repeats.
std::vector<Eigen::Vector2d> ConvexHull2d(std::vector<Eigen::Vector2d> points);

}  // namespace mfp
