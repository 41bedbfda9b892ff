#pragma once
// Body clearance in plan view: the body's plan box (robot_model.h BodyExtent) at a
// configuration against obstacles given as vertical prisms, a convex polygon in plan
// view over a height band (a box terrain's boxes, a map's occupied voxel columns). A prism
// meets the body when their plan shapes overlap and their height bands overlap, the body's
// band taken above the configuration's ground height. Plain Eigen; no I/O.
#include <Eigen/Core>
#include <vector>

#include "planner/robot/robot_model.h"

namespace mfp {

struct BodyObstacle {
  std::vector<Eigen::Vector2d> polygon_world_m;  // convex, counter-clockwise [m]
  double bottom_z_m = 0.0;                       // lowest point [m, world]
  double top_z_m = 0.0;                          // highest point [m, world]
};

// Area of a simple polygon (counter-clockwise positive) [m^2].
double PolygonArea(const std::vector<Eigen::Vector2d>& polygon);

// Area of the intersection of two convex counter-clockwise polygons [m^2].
double ConvexOverlapArea(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b);

// Whether an obstacle reaches into the body's height band when the body stands over
// ground at ground_z_m (strictly: an obstacle whose top lies at the band's bottom does not).
bool InBodyBand(const BodyExtent& body, const BodyObstacle& obstacle, double ground_z_m);

// Largest share of the body's plan box (0..1) that one obstacle in its band covers, for
// the body at (x, y, yaw) over ground at ground_z_m; 0 when the body is unknown.
double BodyOverlapShare(const BodyExtent& body, const std::vector<BodyObstacle>& obstacles, double x_m, double y_m,
                        double yaw_rad, double ground_z_m);
// The same over obstacles[k] for k in `which` only (a caller's nearby subset, without
// copying the obstacles and their polygons).
double BodyOverlapShare(const BodyExtent& body, const std::vector<BodyObstacle>& obstacles,
                        const std::vector<int>& which, double x_m, double y_m, double yaw_rad, double ground_z_m);

}  // namespace mfp
