#pragma once
// The `terrain:` block of scenario files:
//   terrain:
//     resolution: 0.02          # voxel size [m], in [0.001, 1]; default 0.02
//     boxes:
//       - {name: s1, center: [x, y, z], size: [sx, sy, sz], rpy: [roll, pitch, yaw]}
// name and rpy are optional (rpy in radians, default 0). Errors name the file, the key
// and the allowed range.
#include <yaml-cpp/yaml.h>

#include <string>

#include "planner/base/yaml_fields.h"
#include "terrain/terrain_description.h"

namespace mfp {

TerrainDescription ParseTerrainDescription(const YAML::Node& terrain_node, const YamlContext& ctx);

// Reads the `terrain:` block of a scenario file (throws InputError when there is none).
TerrainDescription LoadTerrainDescription(const std::string& scenario_yaml_path);

}  // namespace mfp
