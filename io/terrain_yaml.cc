#include "io/terrain_yaml.h"

#include <cmath>

#include "base/check.h"

namespace mfp {
namespace {

constexpr double kMaxCoordinateM = 1000.0;
constexpr size_t kMaxBoxes = 10000;

Eigen::Vector3d ReadVector3(const YAML::Node& node, const YamlContext& ctx, double min, double max) {
  if (!node.IsSequence() || node.size() != 3) {
    throw InputError(ctx.Where() + ": expected a list of 3 numbers");
  }
  Eigen::Vector3d v;
  for (size_t i = 0; i < 3; ++i) v(static_cast<int>(i)) = ReadDouble(node[i], ctx.Index(i), min, max);
  return v;
}

}  // namespace

TerrainDescription ParseTerrainDescription(const YAML::Node& terrain_node, const YamlContext& ctx) {
  // edge_margin and source are region-extraction settings of scenarios (scenario_yaml.h).
  RejectUnknownKeys(terrain_node, ctx, {"resolution", "boxes", "scan", "noise", "edge_margin", "min_region_area", "overlapping_regions", "source"});
  TerrainDescription terrain;
  if (auto res = OptionalDouble(terrain_node, ctx, "resolution", 0.001, 1.0)) {
    terrain.resolution_m = *res;
  }
  const YAML::Node boxes = terrain_node["boxes"];
  const YamlContext boxes_ctx = ctx.Child("boxes");
  if (!boxes) throw InputError(ctx.Where() + ": missing key 'boxes' (a list of boxes)");
  if (!boxes.IsSequence()) throw InputError(boxes_ctx.Where() + ": expected a list of boxes");
  if (boxes.size() > kMaxBoxes) {
    throw InputError(boxes_ctx.Where() + ": " + std::to_string(boxes.size()) +
                     " boxes, more than the limit of " + std::to_string(kMaxBoxes));
  }
  for (size_t i = 0; i < boxes.size(); ++i) {
    const YAML::Node node = boxes[i];
    const YamlContext box_ctx = boxes_ctx.Index(i);
    RejectUnknownKeys(node, box_ctx, {"name", "center", "size", "rpy"});
    TerrainBox box;
    if (auto name = OptionalString(node, box_ctx, "name")) box.name = *name;
    if (!node["center"]) throw InputError(box_ctx.Where() + ": missing key 'center' ([x, y, z] in m)");
    if (!node["size"]) throw InputError(box_ctx.Where() + ": missing key 'size' ([sx, sy, sz] in m)");
    box.center_world_m =
        ReadVector3(node["center"], box_ctx.Child("center"), -kMaxCoordinateM, kMaxCoordinateM);
    box.size_m = ReadVector3(node["size"], box_ctx.Child("size"), 1e-3, 2 * kMaxCoordinateM);
    if (node["rpy"]) box.rpy_rad = ReadVector3(node["rpy"], box_ctx.Child("rpy"), -2 * M_PI, 2 * M_PI);
    terrain.boxes.push_back(box);
  }
  if (const YAML::Node scan = terrain_node["scan"]) {
    const YamlContext sctx = ctx.Child("scan");
    RejectUnknownKeys(scan, sctx, {"sensors", "max_range"});
    const YAML::Node sensors = scan["sensors"];
    if (!sensors || !sensors.IsSequence() || sensors.size() == 0 || sensors.size() > 1000) {
      throw InputError(sctx.Child("sensors").Where() + ": expected a list of 1 to 1000 [x, y, z] sensor positions");
    }
    for (size_t i = 0; i < sensors.size(); ++i) {
      terrain.scan.sensors_world_m.push_back(
          ReadVector3(sensors[i], sctx.Child("sensors").Index(i), -kMaxCoordinateM, kMaxCoordinateM));
    }
    if (auto range = OptionalDouble(scan, sctx, "max_range", 0.01, 100.0)) terrain.scan.max_range_m = *range;
  }
  if (const YAML::Node noise = terrain_node["noise"]) {
    const YamlContext nctx = ctx.Child("noise");
    RejectUnknownKeys(noise, nctx, {"seed", "jitter", "holes", "outliers"});
    terrain.noise.seed = static_cast<unsigned>(OptionalInt(noise, nctx, "seed", 0, 1 << 30).value_or(1));
    terrain.noise.jitter_fraction = OptionalDouble(noise, nctx, "jitter", 0.0, 1.0).value_or(0.0);
    terrain.noise.hole_fraction = OptionalDouble(noise, nctx, "holes", 0.0, 1.0).value_or(0.0);
    terrain.noise.outliers = OptionalInt(noise, nctx, "outliers", 0, 1000000).value_or(0);
  }
  return terrain;
}

static TerrainDescription LoadTerrainDescriptionUnguarded(const std::string& scenario_yaml_path) {
  const YAML::Node root = LoadYamlFile(scenario_yaml_path);
  const YamlContext ctx{scenario_yaml_path, ""};
  if (!root.IsMap() || !root["terrain"]) {
    throw InputError(scenario_yaml_path + ": missing key 'terrain' (resolution and boxes)");
  }
  return ParseTerrainDescription(root["terrain"], ctx.Child("terrain"));
}

TerrainDescription LoadTerrainDescription(const std::string& scenario_yaml_path) {
  return GuardYaml(scenario_yaml_path, [&] { return LoadTerrainDescriptionUnguarded(scenario_yaml_path); });
}

}  // namespace mfp
