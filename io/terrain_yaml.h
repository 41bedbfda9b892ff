#pragma once
// The `terrain:` block of scenario files:
//   terrain:
//     resolution: 0.02          # voxel size [m], in [0.001, 1]; default 0.02
//     boxes:
//       - {name: s1, center: [x, y, z], size: [sx, sy, sz], rpy: [roll, pitch, yaw]}
//     scan:                     # optional: build the map from sensor rays (free space too)
//       sensors: [[x, y, z], ...]   # ray origins [m]
//       max_range: 6.0              # [m], default 6
//     noise: {seed: 1, jitter: 0.03, holes: 0.01, outliers: 20}   # optional scan noise
// name and rpy are optional (rpy in radians, default 0). jitter and holes are fractions
// of top voxels (terrain_description.h). Errors name the file, the key and the allowed
// range.
#include <yaml-cpp/yaml.h>

#include <string>

#include "geometry/terrain_description.h"
#include "io/yaml_fields.h"

namespace mfp {

TerrainDescription ParseTerrainDescription(const YAML::Node& terrain_node, const YamlContext& ctx);

// Reads the `terrain:` block of a scenario file (throws InputError when there is none).
TerrainDescription LoadTerrainDescription(const std::string& scenario_yaml_path);

}  // namespace mfp
