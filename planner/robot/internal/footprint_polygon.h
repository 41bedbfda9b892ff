#pragma once
// A convex polygon about a leg's nominal foot inside its reachable footprint (the
// footprint's grid of IK-reached cells at the stance height): the leg's real reach, not
// the largest disk about the nominal foot, so it keeps the footprint's asymmetry (a foot
// reaches farther forward than sideways for most legs). Plain Eigen, no I/O.
#include <Eigen/Core>
#include <vector>

#include "planner/robot/internal/footprint_grid.h"
#include "planner/robot/reach_polygon.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// The polygon {w : normal_j . w <= offset_j} about `centre_m` (body frame), with `faces`
// normals equally spaced from +x (at least 3), such that no empty cell of the grid (nor any
// cell outside it) meets it: every point of it is a point the foot reaches. Each face starts
// at the footprint's reach along its normal, and the face a conflicting empty cell lies
// most along is pulled in until it clears that cell, until none conflicts. The grid must
// have had UpdateBoundary() called, and centre_m must lie in an occupied cell.
std::vector<ReachFace> FootprintPolygon(const FootprintGrid& grid, const Eigen::Vector2d& centre_m, int faces);

}  // namespace mfp
