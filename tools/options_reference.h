#pragma once
// The reference of every YAML key (mfp-plan --list-options; docs/options.md is its
// markdown form), gathered from the loaders' option tables.
#include <string>
#include <vector>

#include "io/option_table.h"

namespace mfp {

// Scenario file, the planner: block, robot file, daemon config, in that order.
std::vector<OptionGroup> OptionReference();

// One line per key: key, type, default, unit, advanced, description (and the flat alias).
std::string FormatOptionsText(const std::vector<OptionGroup>& groups);
// docs/options.md: a table per group.
std::string FormatOptionsMarkdown(const std::vector<OptionGroup>& groups);

}  // namespace mfp
