#pragma once
// Which regions a plan can use at all, and which one window of it can: necessary
// conditions from the robot's step limits, so filtering never drops a region a feasible
// plan needs. A foot moves at most step_xy_m horizontally and dz_max_m vertically per
// step, so (1) a region is reachable only through a chain of regions, starting at one
// under a start foot, each within one step of the next, and (2) a window in which each
// leg steps k times can only use regions within k steps of some start foot. Plain Eigen;
// the planner calls it before building each window's MIQP, and route guidance may too.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "base/deadline.h"
#include "geometry/convex_region.h"

namespace mfp {

// Smallest horizontal distance between two regions' polygons (0 when they overlap in
// plan view) [m].
double RegionPlanarDistance(const ConvexRegion& a, const ConvexRegion& b);

// Indices (ascending) of the regions a plan's first steps start from: those holding a
// start foot (within tolerance_m) and, for a start foot no region holds (a robot standing
// on seen surface the regions leave out), every region within one step of it: step_xy_m
// horizontally and dz_max_m vertically.
std::vector<int> StartRegionIndices(const std::vector<ConvexRegion>& regions,
                                    const std::vector<Eigen::Vector3d>& start_feet_world_m, double step_xy_m,
                                    double dz_max_m, double tolerance_m);

// Indices (ascending) of the regions reachable from the start feet: chains of regions
// whose polygons are within step_xy_m horizontally and whose height ranges are within
// dz_max_m, starting at StartRegionIndices.
// nullopt when `deadline` expires (or its stop flag is set) first: the chains compare
// every pair of regions, quadratic in their number, so a large map is checked between
// the regions it visits.
std::optional<std::vector<int>> ReachableRegionIndices(const std::vector<ConvexRegion>& regions,
                                                       const std::vector<Eigen::Vector3d>& start_feet_world_m,
                                                       double step_xy_m, double dz_max_m, double tolerance_m,
                                                       const Deadline& deadline = Deadline());

// Indices (ascending) of the regions a window can use: those within steps_per_leg *
// step_xy_m horizontally and steps_per_leg * dz_max_m vertically of some start foot.
std::vector<int> WindowRegionIndices(const std::vector<ConvexRegion>& regions,
                                     const std::vector<Eigen::Vector3d>& start_feet_world_m,
                                     int steps_per_leg, double step_xy_m, double dz_max_m);

}  // namespace mfp
