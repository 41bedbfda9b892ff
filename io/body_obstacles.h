#pragma once
// A box terrain's boxes as the body's obstacles (body_clearance.h): each box's plan
// outline (the convex hull of its corners in plan view) over the height band its corners
// span; whether one reaches into the body's band is judged per pose. Boxes tilted about x
// or y (ramps the feet stand on) are left out.
#include <vector>

#include "geometry/terrain_description.h"
#include "planner/robot/body_clearance.h"

namespace mfp {

std::vector<BodyObstacle> BoxBodyObstacles(const std::vector<TerrainBox>& boxes);

}  // namespace mfp
