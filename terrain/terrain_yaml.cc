#include "terrain/terrain_yaml.h"

#include <cmath>

#include "planner/base/check.h"

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
  RejectUnknownKeys(terrain_node, ctx, {"resolution", "boxes"});
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
