#pragma once
// SVG picture of a terrain's regions: the height map shaded by height (darker = lower)
// and each region's outline with its id. For mfp-regions --svg.
#include <string>
#include <vector>

#include "terrain/convex_region.h"
#include "terrain/height_map.h"

namespace mfp {

std::string RegionsSvg(const HeightMap& height_map, const std::vector<ConvexRegion>& regions);

}  // namespace mfp
