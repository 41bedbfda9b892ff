#include "tools/daemon/map_regions.h"

#include <algorithm>
#include <limits>

#include "planner/base/check.h"
#include "planner/base/format.h"
#include "terrain/octomap_io.h"
#include "terrain/region_extractor.h"

namespace mfp {
namespace {

// terrain_map_t.format is "bt", "ot" or "" (the content decides); a named format must
// match the content's first line, so a sender's mistake is named, not guessed around.
void CheckMapFormat(const std::string& format, const std::string& bytes, const std::string& what) {
  if (format.empty()) return;
  if (format != "bt" && format != "ot") {
    throw InputError(what + ": format '" + EscapedText(format.substr(0, 64)) +
                     "' is not a map format: give \"bt\", \"ot\" or \"\" (the content decides)");
  }
  const bool binary = bytes.rfind("# Octomap OcTree binary file", 0) == 0;
  const bool full = !binary && bytes.rfind("# Octomap OcTree file", 0) == 0;
  if ((format == "bt" && full) || (format == "ot" && binary)) {
    throw InputError(what + ": format is '" + format + "' but the data is a ." +
                     (binary ? "bt" : "ot") + " map: give the matching format, or \"\"");
  }
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
  return [options](const std::string& bytes, const std::string& format,
                   const std::string& what) {
    CheckMapFormat(format, bytes, what);
    const std::vector<uint8_t> data(bytes.begin(), bytes.end());
    const OccupancyMap map = LoadMapBytes(data, what);
    return ExtractRegions(map, options).regions;
  };
}

}  // namespace mfp
