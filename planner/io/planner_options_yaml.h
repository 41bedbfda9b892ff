#pragma once
// The `planner:` block shared by scenario files and the daemon's config.
#include <yaml-cpp/yaml.h>

#include "planner/base/yaml_fields.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {

// Overrides the fields present in `node` (a mapping); throws InputError naming the file,
// key and allowed range on a bad value or an unknown key.
void ReadPlannerOptions(const YAML::Node& node, const YamlContext& ctx, PlannerOptions* options);

}  // namespace mfp
