#include "io/scenario_yaml.h"

#include <cmath>
#include <limits>

#include "base/check.h"
#include "io/body_obstacles.h"
#include "io/map_file.h"
#include "io/planner_options_yaml.h"
#include "io/terrain_yaml.h"
#include "io/yaml_fields.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/octomap_io.h"

namespace mfp {
namespace {

Pose2D ReadPose(const YAML::Node& node, const YamlContext& ctx) {
  const std::vector<double> v = ReadNumbers(node, ctx, 3);
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d ReadVector3(const YAML::Node& node, const YamlContext& ctx) {
  const std::vector<double> v = ReadNumbers(node, ctx, 3);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

}  // namespace

// The keys of a scenario file; the loader below reads each (the `planner:` block through
// PlannerOptionTable()). Keys of list entries ("[]") are checked where the entries are read.
const OptionTable<Scenario>& ScenarioOptionTable() {
  using S = Scenario;
  static const OptionTable<S> table = {
      LoaderOpt<S>("name", "string", "the file's path", "name in logs and pictures"),
      LoaderOpt<S>("description", "string", "\"\"", "free text, not read"),
      LoaderOpt<S>("robot", "path", "(required)", "robot YAML or URDF, relative to the scenario file"),
      LoaderOpt<S>("start", "[x, y, yaw]", "(required)", "start body pose; the feet stand nominally on the regions below")
          .Unit("m, m, rad"),
      LoaderOpt<S>("goal", "[x, y, yaw]", "(required)", "goal body pose").Unit("m, m, rad"),
      LoaderOpt<S>("max_steps", "int in [1, 100000]", "planner.max_steps",
                   "new footsteps in the plan (the request's; wins over planner.max_steps, so not both)"),
      LoaderOpt<S>("window", "int in [1, 1000]", "planner.window",
                   "new footsteps per MIQP window (the request's; not together with planner.window)"),
      LoaderOpt<S>("time_limit", "number in [0.001, 3600]", "planner.time_limit",
                   "time for the whole plan (the request's; not together with planner.time_limit)")
          .Unit("s"),
      LoaderOpt<S>("planner", "mapping", "{}", "planner options: the planner.* keys below"),
      LoaderOpt<S>("terrain.boxes", "list of boxes", "-",
                   "a course of boxes (one of boxes, regions, map); regions come from their voxel map"),
      LoaderOpt<S>("terrain.boxes[].name", "string", "\"\"", "name of the box"),
      LoaderOpt<S>("terrain.boxes[].center", "[x, y, z]", "(required)", "centre of the box").Unit("m"),
      LoaderOpt<S>("terrain.boxes[].size", "[sx, sy, sz]", "(required)", "size of the box").Unit("m"),
      LoaderOpt<S>("terrain.boxes[].rpy", "[roll, pitch, yaw]", "[0, 0, 0]", "orientation of the box").Unit("rad"),
      LoaderOpt<S>("terrain.resolution", "number in [0.001, 1]", "0.02", "voxel size of the boxes' map").Unit("m"),
      LoaderOpt<S>("terrain.source", "one of extracted, top_faces", "extracted",
                   "boxes: regions extracted from their map, or their exact top faces").Advanced(),
      LoaderOpt<S>("terrain.scan.sensors", "list of [x, y, z]", "-",
                   "boxes seen by rays from these points (free space too) instead of filled in").Unit("m"),
      LoaderOpt<S>("terrain.scan.max_range", "number in [0.01, 100]", "6", "range of the scan's rays").Unit("m"),
      LoaderOpt<S>("terrain.noise.seed", "int in [0, 2^30]", "1", "seed of the scan noise"),
      LoaderOpt<S>("terrain.noise.jitter", "number in [0, 1]", "0", "fraction of top voxels moved up or down"),
      LoaderOpt<S>("terrain.noise.holes", "number in [0, 1]", "0", "fraction of top voxels removed"),
      LoaderOpt<S>("terrain.noise.outliers", "int in [0, 1000000]", "0", "stray voxels added"),
      LoaderOpt<S>("terrain.regions", "list of regions", "-", "convex regions given directly (one of boxes, regions, map)"),
      LoaderOpt<S>("terrain.regions[].vertices", "list of [x, y, z]", "(required)",
                   "a convex polygon on a plane, at most 1000 vertices").Unit("m"),
      LoaderOpt<S>("terrain.regions[].plane_tolerance", "number in [0, 0.1]", "0",
                   "largest distance of a vertex from the polygon's plane").Unit("m"),
      LoaderOpt<S>("terrain.map", "path", "-", "an OctoMap .bt or .ot file (one of boxes, regions, map)"),
      LoaderOpt<S>("terrain.edge_margin", "number in [0, 0.5]", "extractor's",
                   "real surface kept around each foot beyond its radius").Unit("m"),
      LoaderOpt<S>("terrain.min_region_area", "number in [0, 100]", "extractor's",
                   "smallest region of foot centres kept").Unit("m^2"),
      LoaderOpt<S>("terrain.overlapping_regions", "bool", "extractor's", "one patch's regions may overlap")
          .Advanced(),
  };
  return table;
}

// The request's sizes are given at the top of the file or as the planner's defaults,
// not both: the top would win, silently.
namespace {

void RejectShadowedPlannerKeys(const YAML::Node& root, const YamlContext& ctx) {
  const YAML::Node planner = root["planner"];
  if (!planner || !planner.IsMap()) return;
  for (const char* key : {"max_steps", "window", "time_limit"}) {
    if (root[key] && planner[key]) {
      throw InputError(ctx.Child("planner").Child(key).Where() + ": also given as " + key +
                       " at the top of the file, which wins: give only one");
    }
  }
}

}  // namespace

static Scenario LoadScenarioUnguarded(const std::string& path) {
  const YAML::Node root = LoadYamlFile(path);
  const YamlContext ctx{path, ""};
  Scenario s;
  ReadOptions(ScenarioOptionTable(), root, ctx, &s);  // checks the keys; all are read below
  RejectShadowedPlannerKeys(root, ctx);
  s.path = path;
  s.name = OptionalString(root, ctx, "name").value_or(path);
  if (!root["robot"]) throw InputError(ctx.Child("robot").Where() + ": missing (path of a robot YAML or URDF)");
  s.robot_path = ResolveRelative(path, ReadString(root["robot"], ctx.Child("robot")));
  if (!root["start"] || !root["goal"]) throw InputError(ctx.Where() + ": start and goal are required ([x, y, yaw])");
  s.start = ReadPose(root["start"], ctx.Child("start"));
  s.goal = ReadPose(root["goal"], ctx.Child("goal"));
  s.max_steps = OptionalInt(root, ctx, "max_steps", 1, 100000).value_or(0);
  s.window_steps = OptionalInt(root, ctx, "window", 1, 1000).value_or(0);
  s.time_limit_s = OptionalDouble(root, ctx, "time_limit", 1e-3, 3600).value_or(0.0);
  if (root["planner"]) s.warnings = ReadPlannerOptions(root["planner"], ctx.Child("planner"), &s.options);

  if (!root["terrain"]) throw InputError(ctx.Child("terrain").Where() + ": missing (boxes, regions or map)");
  const YAML::Node terrain = root["terrain"];
  const YamlContext tctx = ctx.Child("terrain");
  s.edge_margin_m = OptionalDouble(terrain, tctx, "edge_margin", 0.0, 0.5);
  s.min_region_area_m2 = OptionalDouble(terrain, tctx, "min_region_area", 0.0, 100.0);
  s.overlapping_regions = OptionalBool(terrain, tctx, "overlapping_regions");
  if (terrain["boxes"]) {
    YAML::Node boxes_only;
    boxes_only["boxes"] = terrain["boxes"];
    if (terrain["resolution"]) boxes_only["resolution"] = terrain["resolution"];
    if (terrain["scan"]) boxes_only["scan"] = terrain["scan"];
    if (terrain["noise"]) boxes_only["noise"] = terrain["noise"];
    s.terrain = ParseTerrainDescription(boxes_only, tctx);
  }
  if (const auto source = OptionalString(terrain, tctx, "source")) {
    if (*source == "extracted") {
      s.boxes_source = BoxRegionSource::kExtracted;
    } else if (*source == "top_faces") {
      s.boxes_source = BoxRegionSource::kTopFaces;
    } else {
      throw InputError(tctx.Child("source").Where() + ": '" + *source + "' is not one of extracted, top_faces");
    }
  }
  if (terrain["regions"]) {
    const YAML::Node regions = terrain["regions"];
    const YamlContext rctx = tctx.Child("regions");
    if (!regions.IsSequence()) throw InputError(rctx.Where() + ": expected a list of regions");
    // Caps on listed regions: YAML aliases let a small file name one long polygon many
    // times (an "alias bomb"), so the totals are checked before anything is built.
    constexpr size_t kMaxListedRegions = 100000, kMaxRegionVertices = 1000, kMaxListedVertices = 1000000;
    if (regions.size() > kMaxListedRegions) {
      throw InputError(rctx.Where() + ": " + std::to_string(regions.size()) +
                       " regions, more than the limit of " + std::to_string(kMaxListedRegions));
    }
    size_t total_vertices = 0;
    for (size_t i = 0; i < regions.size(); ++i) {
      const YAML::Node v = regions[i].IsMap() ? regions[i]["vertices"] : YAML::Node();
      const size_t count = v && v.IsSequence() ? v.size() : 0;
      if (count > kMaxRegionVertices) {
        throw InputError(rctx.Index(i).Child("vertices").Where() + ": " + std::to_string(count) +
                         " vertices, more than the limit of " + std::to_string(kMaxRegionVertices));
      }
      total_vertices += count;
      if (total_vertices > kMaxListedVertices) {
        throw InputError(rctx.Where() + ": more than " + std::to_string(kMaxListedVertices) +
                         " vertices in all (YAML aliases count each time they are used)");
      }
    }
    for (size_t i = 0; i < regions.size(); ++i) {
      const YamlContext one = rctx.Index(i);
      RejectUnknownKeys(regions[i], one, {"vertices", "plane_tolerance"});
      if (!regions[i]["vertices"] || !regions[i]["vertices"].IsSequence()) {
        throw InputError(one.Child("vertices").Where() + ": expected a list of [x, y, z] vertices");
      }
      std::vector<Eigen::Vector3d> vertices;
      for (size_t k = 0; k < regions[i]["vertices"].size(); ++k) {
        vertices.push_back(ReadVector3(regions[i]["vertices"][k], one.Child("vertices").Index(k)));
      }
      const double tol = OptionalDouble(regions[i], one, "plane_tolerance", 0.0, 0.1).value_or(0.0);
      try {
        s.listed_regions.push_back(MakeRegionFromPolygon(static_cast<int>(i), vertices, tol));
      } catch (const InputError& e) {
        throw InputError(one.Where() + ": " + e.what());
      }
    }
  }
  if (terrain["map"]) s.map_path = ResolveRelative(path, ReadString(terrain["map"], tctx.Child("map")));
  const int kinds = (s.terrain.boxes.empty() ? 0 : 1) + (s.listed_regions.empty() ? 0 : 1) + (s.map_path.empty() ? 0 : 1);
  if (kinds != 1) {
    throw InputError(tctx.Where() + ": give exactly one of boxes, regions or map (non-empty)");
  }
  return s;
}

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

SeenSurface SeenSurfaceOfLayers(const std::vector<HeightMap>& layers, const std::vector<HeightMap>& moved_as_seen,
                                const std::vector<std::vector<uint8_t>>& filled) {
  SeenSurface seen;
  for (const std::vector<HeightMap>* list : {&layers, &moved_as_seen}) {
    for (size_t l = 0; l < list->size(); ++l) {
      const HeightMap& layer = (*list)[l];
      if (layer.rows <= 0 || layer.cols <= 0) continue;
      seen.grids.push_back(SurfaceGrid{layer.resolution_m, layer.origin_world_m, layer.rows, layer.cols, layer.height_m});
      if (list != &layers || l >= filled.size() || filled[l].size() != layer.height_m.size()) continue;
      std::vector<float>& heights = seen.grids.back().height_m;
      for (size_t i = 0; i < heights.size(); ++i) {
        if (filled[l][i] == kFilledErased) heights[i] = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  return seen;
}

RegionExtractorOptions ScenarioRegionOptions(const Scenario& scenario, const RobotModel& robot,
                                             const Deadline& deadline) {
  // Surfaces need room above them for the robot: its stance height plus a margin.
  const double clearance_m = robot.stance_height_m + scenario.options.body_clearance_margin_m;
  RegionExtractorOptions options;
  options.foot_radius_m = robot.foot_radius_m;
  options.max_slope_rad = robot.max_slope_rad;
  options.clearance_m = clearance_m;
  options.deadline = deadline;
  if (scenario.edge_margin_m) options.edge_margin_m = *scenario.edge_margin_m;
  if (scenario.min_region_area_m2) {
    options.min_region_area_m2 = *scenario.min_region_area_m2;  // exactly as given
    options.min_region_area_voxels = 0.0;
  }
  if (scenario.overlapping_regions) options.overlapping_regions = *scenario.overlapping_regions;
  if (scenario.options.map_body_obstacles) options.body_obstacles = BodyMapObstacleOptions({&robot});
  return options;
}

namespace {

}  // namespace

void TakeBodyObstacles(const RegionExtractionResult& result, ScenarioTerrain* terrain) {
  if (!result.body_obstacles) return;
  if (result.body_obstacles->complete) {
    terrain->map_body_obstacles = PrismBodyObstacles(result.body_obstacles->prisms);
  } else {
    terrain->body_note = result.body_obstacles->message;
  }
}

ScenarioTerrain LoadScenarioTerrain(const Scenario& scenario, const RobotModel& robot, const Deadline& deadline) {
  ScenarioTerrain out;
  if (!scenario.listed_regions.empty()) {
    out.regions = scenario.listed_regions;
    return out;
  }
  const RegionExtractorOptions options = ScenarioRegionOptions(scenario, robot, deadline);
  if (!scenario.map_path.empty()) {
    RegionExtractionResult from_map = ExtractRegionsFromMapFile(scenario.map_path, options);
    out.note = from_map.message;
    out.regions = std::move(from_map.regions);
    out.seen_surface = std::make_shared<const SeenSurface>(SeenSurfaceOfLayers(from_map.layers, from_map.moved_as_seen, from_map.filled));
    TakeBodyObstacles(from_map, &out);
    return out;
  }
  // The boxes' true top faces are the surface a sensor sees from above.
  SeenSurface faces;
  faces.faces = TopFaceRegions(scenario.terrain, 0.0, kPi / 2.0 - 1e-6);
  out.seen_surface = std::make_shared<const SeenSurface>(std::move(faces));
  if (scenario.boxes_source == BoxRegionSource::kTopFaces) {
    // Inset like extracted regions: the foot and the edge margin (the faces are exact: no
    // edge uncertainty).
    out.regions = TopFaceRegions(scenario.terrain, robot.foot_radius_m + options.edge_margin_m, robot.max_slope_rad);
    return out;
  }
  RegionExtractionResult result = ExtractRegionsFromTerrain(scenario.terrain, options);
  out.note = result.message;
  out.regions = std::move(result.regions);
  TakeBodyObstacles(result, &out);
  return out;
}

std::vector<ConvexRegion> ScenarioRegions(const Scenario& scenario, const RobotModel& robot,
                                          std::string* note, const Deadline& deadline) {
  ScenarioTerrain terrain = LoadScenarioTerrain(scenario, robot, deadline);
  if (note != nullptr) *note = terrain.note;
  return std::move(terrain.regions);
}

PlanRequest ScenarioRequest(const Scenario& scenario, const RobotModel& robot,
                            const std::vector<ConvexRegion>& regions) {
  PlanRequest request;
  request.start_feet_world_m =
      NominalStance(robot, regions, scenario.start.x_m, scenario.start.y_m, scenario.start.yaw_rad);
  request.start_yaw_rad = scenario.start.yaw_rad;
  request.goal_x_m = scenario.goal.x_m;
  request.goal_y_m = scenario.goal.y_m;
  request.goal_yaw_rad = scenario.goal.yaw_rad;
  request.max_steps = scenario.max_steps;
  request.window_steps = scenario.window_steps;
  request.time_limit_s = scenario.time_limit_s;
  request.body_obstacles = BoxBodyObstacles(scenario.terrain.boxes);
  return request;
}

PlanRequest ScenarioRequest(const Scenario& scenario, const RobotModel& robot, const ScenarioTerrain& terrain) {
  PlanRequest request = ScenarioRequest(scenario, robot, terrain.regions);
  if (terrain.map_body_obstacles) request.body_obstacles = *terrain.map_body_obstacles;
  for (Eigen::Vector3d& foot : request.start_feet_world_m) {
    if (FindRegionBelow(terrain.regions, foot.x(), foot.y(), 0.0) >= 0) continue;
    if (const std::optional<double> z = HighestSeenSurfaceAt(*terrain.seen_surface, foot.head<2>())) foot.z() = *z;
  }
  request.seen_surface = terrain.seen_surface;
  return request;
}

Scenario LoadScenario(const std::string& path) {
  return GuardYaml(path, [&] { return LoadScenarioUnguarded(path); });
}

std::vector<OptionDoc> ScenarioOptionDocs() {
  return DocumentOptions(ScenarioOptionTable(), "", Scenario{});
}

}  // namespace mfp
