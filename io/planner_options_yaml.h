#pragma once
// The `planner:` block shared by scenario files and the daemon's config. Its keys are the
// table PlannerOptionTable(): sections mirror the option structs (search:, formulation:,
// relax_and_fix:, polish:, solvers:, route:, windows:); the flat keys of older files
// are read as aliases, with a warning. docs/options.md lists every key.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "io/option_table.h"
#include "io/yaml_fields.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {

const OptionTable<PlannerOptions>& PlannerOptionTable();

// Overrides the fields present in `node` (a mapping); throws InputError naming the file,
// key and allowed range on a bad value, an unknown key (with a suggestion), or a key
// given both by its section and by its flat alias. Returns the warnings (flat keys read).
std::vector<std::string> ReadPlannerOptions(const YAML::Node& node, const YamlContext& ctx,
                                            PlannerOptions* options);

// The reference entries of the `planner:` block, keys prefixed with `prefix`.
std::vector<OptionDoc> PlannerOptionDocs(const std::string& prefix = "planner.");

}  // namespace mfp
