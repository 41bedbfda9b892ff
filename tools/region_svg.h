#pragma once
// SVG picture of a terrain's regions: the height map shaded by height (darker = lower)
// and each region's outline with its id. For mfp-regions --svg. With several surface
// levels (floors under tables, ground under bridges), one panel per level, side by side,
// each with the regions on that level.
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "terrain/extraction/height_map.h"

namespace mfp {

std::string RegionsSvg(const HeightMap& height_map, const std::vector<ConvexRegion>& regions);

// region_layer[i]: the level of regions[i] (RegionExtractionResult::region_layer).
std::string RegionsSvg(const std::vector<HeightMap>& levels, const std::vector<ConvexRegion>& regions,
                       const std::vector<int>& region_layer);

}  // namespace mfp
