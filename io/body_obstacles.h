#pragma once
// A box terrain's boxes as the body's obstacles (body_clearance.h): each box's plan
// outline (the convex hull of its corners in plan view) over the height band its corners
// span; whether one reaches into the body's band is judged per pose. Boxes tilted about x
// or y (ramps the feet stand on) are left out.
#include <optional>
#include <vector>

#include "geometry/terrain_description.h"
#include "planner/robot/body_clearance.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/map_body_obstacles.h"

namespace mfp {

std::vector<BodyObstacle> BoxBodyObstacles(const std::vector<TerrainBox>& boxes);

// A map's obstacle prisms (map_body_obstacles.h) as the body's obstacles.
std::vector<BodyObstacle> PrismBodyObstacles(const std::vector<MapPrism>& prisms);

// What can reach the band of any of `robots`' bodies: the lowest band bottom and the
// farthest a foot stands from its body's plan box (the box's circumscribed radius, the
// farthest nominal foot and the reach square's diagonal, l_bnd + d_lim per axis). Nullopt
// when no robot's body is known (nothing to keep clear).
std::optional<MapObstacleOptions> BodyMapObstacleOptions(const std::vector<const RobotModel*>& robots);

}  // namespace mfp
