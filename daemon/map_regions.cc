#include "daemon/map_regions.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>

#include "base/check.h"
#include "base/format.h"
#include "daemon/height_map_message.h"
#include "io/body_obstacles.h"
#include "io/scenario_yaml.h"
#include "terrain/extraction/height_grid.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/octomap_io.h"

namespace mfp {
namespace {

// terrain_map_t.format is "bt", "ot" or "" (DESIGN.md); anything else is a sender's
// mistake, named. The content decides between .bt and .ot (CheckOctreeStream reads either),
// as mfp-make-log's logs label a map by its file name.
void CheckMapFormat(const std::string& format, const std::string& what) {
  if (format.empty() || format == "bt" || format == "ot") return;
  throw InputError(what + ": format '" + EscapedText(format.substr(0, 64)) +
                   "' is not a map format: give \"bt\", \"ot\" or \"\" (the content decides)");
}

}  // namespace

MapFunction MakeOctomapMapFunction(const DaemonSetup& setup) {
  // One region set serves every robot: inset by the widest foot and limited to the
  // gentlest max_slope, so no robot is sent onto a surface it cannot take.
  RegionExtractorOptions options;
  options.foot_radius_m = 0.0;
  options.max_slope_rad = 1.5;
  // Surfaces keep the room the tallest robot needs above them.
  options.clearance_m = 0.0;
  const double margin_m = PlannerOptions().body_clearance_margin_m;
  for (const auto& entry : setup.robots) {
    options.clearance_m = std::max(options.clearance_m, entry.second.stance_height_m + margin_m);
    options.foot_radius_m = std::max(options.foot_radius_m, entry.second.foot_radius_m);
    options.max_slope_rad = std::min(options.max_slope_rad, entry.second.max_slope_rad);
  }
  if (!(options.clearance_m > 0.0)) options.clearance_m = std::numeric_limits<double>::infinity();
  options.threads = setup.config.limits.extraction_threads;
  if (setup.config.planner.map_body_obstacles) {
    // One obstacle set for every robot: the lowest body band and the farthest reach.
    std::vector<const RobotModel*> robots;
    for (const auto& entry : setup.robots) robots.push_back(&entry.second);
    options.body_obstacles = BodyMapObstacleOptions(robots);
  }
  const size_t max_map_bytes = setup.config.limits.max_map_bytes;
  return [options, max_map_bytes](const std::string& bytes, const std::string& format,
                                   const std::string& what) {
    RegionExtractionResult result;
    if (format == kHeightMapFormat) {
      result = ExtractRegionsFromHeightGrid(HeightGridFromBytes(bytes, max_map_bytes, what), options);
    } else {
      CheckMapFormat(format, what);
      const std::vector<uint8_t> data(bytes.begin(), bytes.end());
      result = ExtractRegions(LoadMapBytes(data, what), options);
    }
    // The surface layers the regions were cut from: where a start foot may stand.
    MapTerrain terrain{std::move(result.regions),
                       std::make_shared<const SeenSurface>(SeenSurfaceOfLayers(result.layers, result.moved_as_seen, result.filled)),
                       nullptr, ""};
    if (result.body_obstacles && result.body_obstacles->complete) {
      terrain.body_obstacles =
          std::make_shared<const std::vector<BodyObstacle>>(PrismBodyObstacles(result.body_obstacles->prisms));
    } else if (result.body_obstacles) {
      terrain.body_note = result.body_obstacles->message;
    }
    return terrain;
  };
}

}  // namespace mfp
