// mfp-regions MAP: the convex safe regions of an OctoMap map (.bt or .ot) or a height map, as a table,
// JSON ({"regions": [...]}) and SVG; --region ID prints one region's faces and vertices;
// --body-of ROBOT also finds the map's obstacles to that robot's body and prints their count.
// Exit 0 on success (also when the map has no regions: the reason is printed), 2 on bad
// input with the problem on stderr.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "base/check.h"
#include "io/body_obstacles.h"
#include "io/cli_parse.h"
#include "io/height_map_file.h"
#include "io/region_json.h"
#include "io/robot_loader.h"
#include "io/text_output.h"
#include "terrain/extraction/height_grid.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/octomap_io.h"
#include "tools/region_svg.h"

namespace {

Eigen::Vector3d Centroid(const mfp::ConvexRegion& r) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& v : r.vertices_world_m) c += v;
  return c / static_cast<double>(r.vertices_world_m.size());
}

void PrintBodyObstacles(const mfp::MapObstacles& o) {
  if (!o.complete) {
    std::printf("%s\n", o.message.c_str());
    return;
  }
  std::printf("body obstacles: %zu prisms over %lld of %lld occupied column runs (the others within the floor band) "
              "in %.1f ms\n",
              o.prisms.size(), static_cast<long long>(o.runs_above_floor), static_cast<long long>(o.voxel_runs),
              1e3 * o.time_s);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Convex safe regions of an OctoMap terrain map"};
  std::string map_path, json_path, svg_path;
  int region_id = -1;
  mfp::RegionExtractorOptions options;
  app.add_option("map", map_path, "map file (.bt or .ot), or a height map (.npy with its .yaml, or the .yaml)")->required();
  app.add_option("--json", json_path, "write {\"regions\": [...]} to FILE ('-' = stdout)");
  app.add_option("--svg", svg_path, "write a picture (heights shaded, regions outlined) to FILE");
  app.add_option("--region", region_id, "print the faces (A, b) and vertices of region ID");
  app.add_option("--foot-radius", options.foot_radius_m, "foot radius the regions are inset by [m]")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--max-slope", options.max_slope_rad, "steepest walkable surface [rad]")
      ->check(CLI::Range(0.0, M_PI / 2));
  double time_limit_s = 0.0;
  app.add_option("--time-limit", time_limit_s,
                 "seconds for loading and extraction; when they run out, the regions of the "
                 "patches done so far (largest first) and a line saying so")
      ->check(CLI::Range(1e-3, 3600.0));
  app.add_option("--clearance", options.clearance_m,
                 "free space a surface needs above it [m] (the robot's stance height plus a margin; "
                 "default: only the highest surface of each column)")
      ->check(CLI::Range(0.001, 1000.0));
  app.add_option("--edge-margin", options.edge_margin_m, "real surface kept around a foot [m]")
      ->check(CLI::Range(0.0, 1.0));
  std::string body_robot_path;
  app.add_option("--body-of", body_robot_path,
                 "robot file (YAML or URDF): also find the map's obstacles to its body and print their count");
  MFP_CLI_PARSE(app, argc, argv);
  if (time_limit_s > 0) options.deadline = mfp::Deadline::After(time_limit_s);
  try {
    if (!body_robot_path.empty()) {
      const mfp::RobotModel robot = mfp::LoadRobot(body_robot_path);
      options.body_obstacles = mfp::BodyMapObstacleOptions({&robot});
      if (!options.body_obstacles) throw mfp::InputError("--body-of " + body_robot_path + ": the robot's body is unknown");
    }
    const bool height_map = mfp::IsHeightMapPath(map_path);
    const mfp::OccupancyMap map = height_map ? mfp::OccupancyMap() : mfp::LoadMapFile(map_path);
    const mfp::RegionExtractionResult result =
        height_map ? mfp::ExtractRegionsFromHeightGrid(mfp::LoadHeightGridFile(map_path), options)
                   : mfp::ExtractRegions(map, options);
    if (!json_path.empty()) mfp::WriteTextOutput(json_path, mfp::RegionsToJson(result.regions).dump(2) + "\n");
    if (!svg_path.empty()) mfp::WriteTextOutput(svg_path, mfp::RegionsSvg(result.layers, result.regions, result.region_layer));
    if (region_id >= 0 || app.count("--region") > 0) {
      if (region_id < 0 || region_id >= static_cast<int>(result.regions.size())) {
        throw mfp::InputError("--region " + std::to_string(region_id) + ": the map has " +
                              std::to_string(result.regions.size()) + " regions (ids 0.." +
                              std::to_string(static_cast<int>(result.regions.size()) - 1) + ")");
      }
      const mfp::ConvexRegion& r = result.regions[static_cast<size_t>(region_id)];
      std::printf("region %d: area %.4f m^2, slope %.4f rad, plane tolerance %.4f m\n", r.id,
                  r.area_m2, r.SlopeRad(), r.plane_tolerance_m);
      std::printf("faces (a_x a_y a_z <= b):\n");
      for (Eigen::Index j = 0; j < r.A.rows(); ++j) {
        std::printf("  %+.6f %+.6f %+.6f <= %+.6f%s\n", r.A(j, 0), r.A(j, 1), r.A(j, 2), r.b(j),
                    j >= r.A.rows() - 2 ? "   (plane)" : "");
      }
      std::printf("vertices (x y z, counter-clockwise):\n");
      for (const auto& v : r.vertices_world_m) std::printf("  %.4f %.4f %.4f\n", v.x(), v.y(), v.z());
      return 0;
    }
    if (json_path == "-") return 0;  // stdout holds the JSON only
    if (height_map) {
      std::printf("%s: height map %d x %d at %.3f m, %d known cells, %d planar patches (%d too steep, "
                  "%d too small), %zu regions in %.1f ms\n",
                  map_path.c_str(), result.height_map.cols, result.height_map.rows, result.height_map.resolution_m,
                  result.stats.surface_cells, result.stats.patches, result.stats.patches_too_steep,
                  result.stats.patches_too_small, result.regions.size(), 1e3 * result.stats.total_s);
    } else {
    std::printf("%s: %zu occupied leaves (%zu free) at %.3f m, %d surface cells on %d levels "
                "(%d without room above, %d not seen from above, %d outlier voxels), %d planar patches "
                "(%d too steep, %d too small), %zu regions in %.1f ms\n",
                map_path.c_str(), map.leaves.size(), map.free_leaves.size(), map.resolution_m,
                result.stats.surface_cells, result.stats.layers, result.stats.no_room_above,
                result.stats.not_seen_from_above, result.stats.isolated_voxels, result.stats.patches,
                result.stats.patches_too_steep, result.stats.patches_too_small, result.regions.size(),
                1e3 * result.stats.total_s);
    }
    if (result.body_obstacles) PrintBodyObstacles(*result.body_obstacles);
    if (result.regions.empty() || result.stopped) std::printf("%s\n", result.message.c_str());
    if (result.regions.empty()) return 0;
    std::printf("%4s %10s %9s %9s %8s %6s\n", "id", "area_m2", "slope_deg", "height_m", "vertices", "level");
    for (const mfp::ConvexRegion& r : result.regions) {
      std::printf("%4d %10.4f %9.2f %9.3f %8zu %6d\n", r.id, r.area_m2, r.SlopeRad() * 180.0 / M_PI,
                  Centroid(r).z(), r.vertices_world_m.size(), result.region_layer[static_cast<size_t>(r.id)]);
    }
  } catch (const mfp::InputError& e) {
    std::fprintf(stderr, "mfp-regions: %s\n", e.what());
    return 2;
  }
  return 0;
}
