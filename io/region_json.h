#pragma once
// The region object of the plan JSON and of `mfp-regions --json`:
//   {"id", "A": [[a_x, a_y, a_z], ...], "b": [...], "vertices": [[x, y, z], ...],
//    "area", "slope", "normal", "plane_tolerance"}
#include <nlohmann/json.hpp>
#include <vector>

#include "geometry/convex_region.h"

namespace mfp {

nlohmann::json RegionToJson(const ConvexRegion& region);

// {"regions": [...]}
nlohmann::json RegionsToJson(const std::vector<ConvexRegion>& regions);

}  // namespace mfp
