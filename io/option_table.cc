#include "io/option_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "base/check.h"

namespace mfp {
namespace option_table_internal {
namespace {

std::string SectionOf(const std::string& key) { return SplitKey(key).first; }

// Sections directly under `section` that hold keys ("search" under "").
std::set<std::string> ChildSections(const std::vector<std::string>& keys, const std::string& section) {
  std::set<std::string> children;
  const std::string prefix = section.empty() ? "" : section + ".";
  for (const std::string& key : keys) {
    const std::string s = SectionOf(key);
    if (s.size() <= prefix.size() || s.compare(0, prefix.size(), prefix) != 0) continue;
    children.insert(s.substr(prefix.size(), s.find('.', prefix.size()) - prefix.size()));
  }
  return children;
}

// The keys of other sections with this name: "planner.polish.time_limit" for `time_limit`
// under search, say ("" when none).
std::string ElsewhereHint(const std::string& name, const std::string& section,
                          const std::vector<std::string>& keys, const std::string& block_path) {
  std::string hint;
  for (const std::string& key : keys) {
    const auto [s, n] = SplitKey(key);
    if (n != name || s == section) continue;
    hint += (hint.empty() ? "" : " or ") + (block_path.empty() ? key : block_path + "." + key);
  }
  return hint;
}

void CheckMap(const YAML::Node& map, const YamlContext& block_ctx, const std::string& section,
              const std::vector<std::string>& keys, const std::vector<std::string>& aliases) {
  const YamlContext ctx = ContextAt(block_ctx, section);
  std::vector<std::string> allowed;
  for (const std::string& key : keys) {
    if (SectionOf(key) == section) allowed.push_back(SplitKey(key).second);
  }
  for (const std::string& child : ChildSections(keys, section)) allowed.push_back(child);
  if (section.empty()) allowed.insert(allowed.end(), aliases.begin(), aliases.end());
  if (map.IsMap()) {
    const std::set<std::string> ok(allowed.begin(), allowed.end());
    for (const auto& kv : map) {
      if (!kv.first.IsScalar() || ok.count(kv.first.Scalar())) continue;
      const std::string hint = ElsewhereHint(kv.first.Scalar(), section, keys, block_ctx.path);
      if (!hint.empty()) {
        throw InputError(ctx.Where() + ": unknown key '" + kv.first.Scalar() + "' here; did you mean " + hint + "?");
      }
    }
  }
  RejectUnknownKeys(map, ctx, allowed);
}

}  // namespace

std::pair<std::string, std::string> SplitKey(const std::string& key) {
  const size_t dot = key.rfind('.');
  if (dot == std::string::npos) return {"", key};
  return {key.substr(0, dot), key.substr(dot + 1)};
}

YAML::Node NodeAt(const YAML::Node& block, const std::string& section) {
  if (section.empty()) return block;
  if (!block.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const size_t dot = section.find('.');
  const YAML::Node child = block[section.substr(0, dot)];
  if (!child || !child.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  return dot == std::string::npos ? child : NodeAt(child, section.substr(dot + 1));
}

YamlContext ContextAt(const YamlContext& block_ctx, const std::string& section) {
  return section.empty() ? block_ctx : block_ctx.Child(section);
}

void CheckKeys(const YAML::Node& block, const YamlContext& ctx, const std::vector<std::string>& keys,
               const std::vector<std::string>& aliases) {
  std::set<std::string> sections = {""};
  for (const std::string& key : keys) {
    for (std::string s = SectionOf(key); !s.empty(); s = SectionOf(s)) sections.insert(s);
  }
  for (const std::string& section : sections) {  // parents before children: "" < "a" < "a.b"
    if (section.empty()) {
      CheckMap(block, ctx, section, keys, aliases);
      continue;
    }
    const auto [parent_section, name] = SplitKey(section);
    const YAML::Node parent = NodeAt(block, parent_section);
    if (!parent) continue;
    const YAML::Node map = parent[name];
    if (!map) continue;
    // `polish: false` is the old flat key of polish.enabled, not the polish section.
    const bool flat_key = parent_section.empty() && std::find(aliases.begin(), aliases.end(), name) != aliases.end();
    if (!map.IsMap() && flat_key) continue;
    CheckMap(map, ctx, section, keys, aliases);  // "expected a mapping" when it is not one
  }
}

YAML::Node FindValue(const YAML::Node& block, const YamlContext& ctx, const std::string& key,
                     const std::string& alias, YamlContext* where, std::vector<std::string>* warnings) {
  const auto [section, name] = SplitKey(key);
  const YAML::Node parent = NodeAt(block, section);
  const YAML::Node value = parent ? parent[name] : YAML::Node(YAML::NodeType::Undefined);
  // A mapping under the alias's name is the section of the same name (`polish: {...}`).
  // (Nodes are built, never assigned: assigning a YAML::Node writes into the document.)
  const YAML::Node at_alias = alias.empty() ? YAML::Node(YAML::NodeType::Undefined) : block[alias];
  const bool is_section = at_alias && at_alias.IsMap() && section.rfind(alias, 0) == 0;
  const YAML::Node flat = is_section ? YAML::Node(YAML::NodeType::Undefined) : at_alias;
  const YamlContext key_ctx = ContextAt(ctx, key);
  if (value && flat) {
    throw InputError(ctx.Child(alias).Where() + ": '" + alias + "' is the old flat name of " + key_ctx.path +
                     ", which is also given and wins: remove '" + alias + "'");
  }
  if (flat) {
    *where = ctx.Child(alias);
    warnings->push_back(where->Where() + ": flat key '" + alias + "' is deprecated: write " + key_ctx.path +
                        " (flat keys are accepted until the next release)");
    return flat;
  }
  *where = key_ctx;
  return value;
}

std::string EnumName(const YamlContext& where, const std::string& name, const std::vector<std::string>& names,
                     size_t* index) {
  std::string allowed;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) {
      *index = i;
      return name;
    }
    allowed += (i ? ", " : "") + names[i];
  }
  throw InputError(where.Where() + ": '" + name + "' is not one of " + allowed);
}

std::vector<double> NumberList(const YAML::Node& node, const YamlContext& where, double min, bool min_exclusive,
                               double max) {
  const std::vector<double> values = ReadNumbers(node, where, -1);
  for (double v : values) {
    if ((min_exclusive ? v <= min : v < min) || v > max) {
      throw InputError(where.Where() + ": each entry must lie in " +
                       FormatRange(OptionKind::kNumberList, min, max, min_exclusive) + ", got " + FormatNumber(v));
    }
  }
  return values;
}

std::string FormatNumber(double value) {
  // The shortest text that reads back as the same double.
  // Integer parts in full (30, not 3e+01).
  const int digits = std::fabs(value) >= 1.0 ? static_cast<int>(std::floor(std::log10(std::fabs(value)))) + 1 : 1;
  char text[64];
  for (int precision = std::min(digits, 17); precision <= 17; ++precision) {
    std::snprintf(text, sizeof(text), "%.*g", precision, value);
    if (std::stod(text) == value) break;
  }
  return text;
}

std::string FormatRange(OptionKind kind, double min, double max, bool min_exclusive) {
  if (kind != OptionKind::kInt && kind != OptionKind::kDouble && kind != OptionKind::kNumberList) return "";
  std::ostringstream out;
  out.precision(6);
  if (kind == OptionKind::kInt) {
    out << "[" << static_cast<long long>(min) << ", " << static_cast<long long>(max) << "]";
  } else {
    out << (min_exclusive ? "(" : "[") << min << ", " << max << "]";
  }
  return out.str();
}

}  // namespace option_table_internal
}  // namespace mfp
