#pragma once
// A safe region for footsteps: a convex polygon lying on a plane in the world frame,
// written as A f <= b (the polygon's edges as vertical half-spaces, and the plane as two
// inequalities a tolerance apart). Plain Eigen; produced by the terrain extractor and
// by scenario files, consumed by the planner.
#include <Eigen/Core>
#include <vector>

namespace mfp {

struct ConvexRegion {
  int id = -1;
  // Rows a_j of A and entries b_j: a_j . f <= b_j for f in the world frame [m].
  Eigen::Matrix<double, Eigen::Dynamic, 3> A;
  Eigen::VectorXd b;
  // Polygon boundary on the plane, counter-clockwise seen from above [m, world].
  std::vector<Eigen::Vector3d> vertices_world_m;
  // Upward unit normal of the supporting plane (world).
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();
  double plane_tolerance_m = 0.0;  // half-thickness of the plane slab [m]
  double area_m2 = 0.0;            // area of the polygon on its plane [m^2]

  // Height of the supporting plane at (x, y) [m].
  double HeightAt(double x_m, double y_m) const;
  // Slope of the plane from horizontal [rad].
  double SlopeRad() const;
};

// Builds a region from the vertices of a convex polygon lying on one plane. The
// vertices may be given in either winding; collinear and duplicate points are dropped.
// Throws InputError when there are fewer than 3 distinct vertices, the polygon is not
// convex, the points are not coplanar within plane_tolerance_m, the plane is vertical,
// or any number is not finite.
ConvexRegion MakeRegionFromPolygon(int id, const std::vector<Eigen::Vector3d>& vertices_world_m,
                                   double plane_tolerance_m);

// True when every inequality holds within tolerance_m.
bool RegionContains(const ConvexRegion& region, const Eigen::Vector3d& point_world_m,
                    double tolerance_m);

// Largest violation max_j (a_j . f - b_j), negative inside [m].
double RegionViolation(const ConvexRegion& region, const Eigen::Vector3d& point_world_m);

// Distance in plan view (x, y) from xy_m to the region's polygon, 0 inside or on its
// boundary [m]. The polygon's vertices are counter-clockwise, as MakeRegionFromPolygon
// leaves them.
double PlanDistanceToRegion(const ConvexRegion& region, const Eigen::Vector2d& xy_m);

// The point of segment [a, b] nearest to p (a itself when the segment has no length).
Eigen::Vector2d ClosestPointOnSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Distance from p to segment [a, b], in the units of the points.
inline double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (ClosestPointOnSegment(p, a, b) - p).norm();
}

// The point of a closed polygon's boundary (vertices in order, either way round) nearest
// to xy_m in plan view [m]. Inside or out: callers that want xy_m itself when inside
// check that first.
Eigen::Vector2d ClosestBoundaryPoint(const std::vector<Eigen::Vector2d>& polygon_m, const Eigen::Vector2d& xy_m);

// Index (into regions) of the highest region whose polygon contains (x, y) within
// tolerance_m horizontally (the surface a foot would stand on), or -1 when none does.
int FindRegionBelow(const std::vector<ConvexRegion>& regions, double x_m, double y_m,
                    double tolerance_m);

}  // namespace mfp
