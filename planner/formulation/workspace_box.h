#pragma once
// The workspace box: every footstep lies in some region, so in the bounding box of the
// regions' vertices (grown by each region's plane tolerance on z) and the start stance.
// Bounds of the footstep variables, and the box over which big-M constants are taken.
#include <Eigen/Core>
#include <vector>

#include "geometry/convex_region.h"
#include "planner/miqp/miqp.h"

namespace mfp {

struct Box3 {  // axis-aligned, empty until a point is added
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInfinity);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-kInfinity);
  void Add(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

// The regions' box and the start feet, grown by 1 mm on every side.
Box3 MakeWorkspaceBox(const std::vector<ConvexRegion>& regions, const std::vector<Eigen::Vector3d>& start_feet_world_m);

// Largest value of a . f - b over the box (corners suffice: it is linear).
double MaxOverBox(const Eigen::Vector3d& a, double b, const Box3& box);

}  // namespace mfp
