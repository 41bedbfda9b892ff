#pragma once
// The plan-view moves one step of a foot can make under the robot's reach model
// (robot_model.h): the new foot lies in the reach polygon (box, octagon or 16-gon, half-width d_lim)
// about its previous nominal spot, and the previous foot stood in the reference box
// (half-side l_bnd) about that spot, so the step f_i - f_i-n lies in their Minkowski sum,
// the step polygon. Two regions one step bridges are those whose gap that polygon spans:
// the route graph joins exactly those, so it joins only what a window can cross. No I/O.
#include <Eigen/Core>
#include <vector>

#include "planner/robot/robot_model.h"

namespace mfp {

// The reach polygon about the origin, counter-clockwise: the box's 4 corners, the
// octagon's 8 or the 16-gon's 16 [m].
std::vector<Eigen::Vector2d> ReachPolygon(ReachShape shape, double half_width_m);

// The corners of a footprint polygon (LegModel::footprint_faces), counter-clockwise, about
// the nominal foot (the faces clipped from a box 10 times the largest offset) [m].
std::vector<Eigen::Vector2d> ReachFaceCorners(const std::vector<ReachFace>& faces);

// For the footprint shape: the smallest face offset over the legs' polygons [m]: how far a
// foot may stand from its nominal spot in every direction (the polygon's inscribed disk
// about it).
double FootprintInscribedReach(const RobotModel& robot);

// Every move f_i - f_i-n of a later step (not a leg's first): the reach polygon plus the
// reference box, counter-clockwise [m]. For the footprint shape, the regular 16-gon of
// apothem FootprintStepWidth: every move at some yaw, and more.
std::vector<Eigen::Vector2d> StepPolygon(const RobotModel& robot);

// For the footprint shape: the smallest over the legs of the polygon's widest width (its
// diameter), how far one foot moves from one side of its polygon to the other [m].
double FootprintStepWidth(const RobotModel& robot);

// How far one step spans on an axis, for the route graph's quick test and the messages:
// d_lim + l_bnd, or for the footprint shape FootprintStepWidth [m].
double AxisStepSpan(const RobotModel& robot);
// What AxisStepSpan is, for messages: "d_lim + l_bnd" or "the footprint polygon's width".
const char* AxisStepSpanName(const RobotModel& robot);

// A leg's footprint polygon: its farthest corner from the nominal foot [m].
double FootprintFarthestCorner(const LegModel& leg);

// A leg's footprint polygon's diameter, the largest distance between two of its corners
// [m]: how far the foot moves between two points of the polygon turned by one yaw.
double FootprintDiameter(const LegModel& leg);

// The smallest t >= 0 such that a + t * step meets b (Minkowski sum), for convex polygons a
// and b (plan view, either orientation, at least one point each) and a convex polygon
// `step` that holds the origin inside: t <= 1 when one move of `step` bridges the gap
// from a to b; 0 when they meet. Exact (separating axes over the three polygons' edges).
double StepsToBridge(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                     const std::vector<Eigen::Vector2d>& step);

// How far `step` reaches from the origin along the direction d (not zero) [m].
double StepReachAlong(const std::vector<Eigen::Vector2d>& step, const Eigen::Vector2d& d);

}  // namespace mfp
