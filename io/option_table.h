#pragma once
// Options as tables, one per options struct (as HiGHS's option records): each key names
// its member, range, unit, default (read from a default-constructed struct), a one-line
// description and whether it is advanced. The YAML loaders read their keys through the
// tables, and the reference (mfp-plan --list-options, docs/options.md) is printed from
// the same tables, so the two cannot drift apart.
//
// A key may sit in a section ("search.max_nodes" is `search: {max_nodes: ...}` in YAML)
// and may have an alias, the flat key older files used: an alias is read with a warning,
// and giving both the key and its alias is an error naming the key that wins.
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/yaml_fields.h"

namespace mfp {

// A key as the reference lists it.
struct OptionDoc {
  std::string key;            // dotted path from the file's top: "planner.search.max_nodes"
  std::string type;           // "int in [1, 64]", "bool", "one of big_m, convex_hull", ...
  std::string default_value;  // as it would be written in YAML
  std::string unit;           // SI unit, "" when none
  std::string description;    // one line
  bool advanced = false;      // for measurements and tuning; defaults are the product's choice
  std::string alias;          // flat key of older files, accepted with a warning ("" = none)
};

// The keys of one kind of file (or one block of it), in the reference.
struct OptionGroup {
  std::string title;  // "scenario file", "daemon config (config/daemon.yaml)"
  std::string note;   // one line on where these keys are written
  std::vector<OptionDoc> options;
};

// A reference to a member of Root, possibly nested: In(&Root::sub, &Sub::field).
template <class Root, class T>
struct Ref {
  std::function<T&(Root&)> at;
};
template <class Root, class T>
Ref<Root, T> At(T Root::*field) {
  return {[field](Root& r) -> T& { return r.*field; }};
}
template <class Root, class Sub, class T>
Ref<Root, T> In(Sub Root::*sub, T Sub::*field) {
  return {[sub, field](Root& r) -> T& { return (r.*sub).*field; }};
}

enum class OptionKind { kInt, kDouble, kBool, kEnum, kNumberList, kString, kByLoader };

// One key of a table. Build it with Opt(...), EnumOpt(...), ListOpt(...), LoaderOpt(...).
template <class Root>
struct Option {
  std::string key;  // within the table's block: "max_steps", "search.max_nodes"
  OptionKind kind = OptionKind::kByLoader;
  double min = 0.0, max = 0.0;  // ints and doubles; each entry of a number list
  bool min_exclusive = false;   // number lists: (min, max]
  std::function<int&(Root&)> int_at;
  std::function<double&(Root&)> double_at;
  std::function<bool&(Root&)> bool_at;
  std::function<std::string&(Root&)> string_at;
  std::function<std::vector<double>&(Root&)> list_at;
  std::vector<std::string> enum_names;
  std::function<void(Root&, size_t)> enum_set;
  std::function<size_t(const Root&)> enum_get;
  std::string loader_type, loader_default;  // kByLoader: what the reference says
  std::string unit, description, alias;
  bool advanced = false;

  Option& Alias(std::string flat_key) { alias = std::move(flat_key); return *this; }
  Option& Advanced() { advanced = true; return *this; }
  Option& Unit(std::string u) { unit = std::move(u); return *this; }
};

template <class Root>
using OptionTable = std::vector<Option<Root>>;

// The parts every option has; each maker below adds where its value lives and its range.
template <class Root>
Option<Root> BaseOption(std::string key, OptionKind kind, std::string description) {
  Option<Root> o;
  o.key = std::move(key), o.kind = kind, o.description = std::move(description);
  return o;
}

template <class Root>
Option<Root> Opt(std::string key, Ref<Root, int> ref, int min, int max, std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kInt, std::move(description));
  o.int_at = ref.at, o.min = min, o.max = max;
  return o;
}
template <class Root>
Option<Root> Opt(std::string key, Ref<Root, double> ref, double min, double max, std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kDouble, std::move(description));
  o.double_at = ref.at, o.min = min, o.max = max;
  return o;
}
template <class Root>
Option<Root> Opt(std::string key, Ref<Root, bool> ref, std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kBool, std::move(description));
  o.bool_at = ref.at;
  return o;
}
template <class Root>
Option<Root> Opt(std::string key, Ref<Root, std::string> ref, std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kString, std::move(description));
  o.string_at = ref.at;
  return o;
}
// A list of numbers, each in [min, max] (or (min, max] with min_exclusive).
template <class Root>
Option<Root> ListOpt(std::string key, Ref<Root, std::vector<double>> ref, double min, bool min_exclusive,
                     double max, std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kNumberList, std::move(description));
  o.list_at = ref.at, o.min = min, o.min_exclusive = min_exclusive, o.max = max;
  return o;
}
// An enum member written as one of `names` (name, value pairs).
template <class Root, class E>
Option<Root> EnumOpt(std::string key, Ref<Root, E> ref, std::vector<std::pair<std::string, E>> names,
                     std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kEnum, std::move(description));
  std::vector<E> values;
  for (const auto& n : names) {
    o.enum_names.push_back(n.first);
    values.push_back(n.second);
  }
  o.enum_set = [ref, values](Root& r, size_t i) { ref.at(r) = values[i]; };
  o.enum_get = [ref, values](const Root& r) -> size_t {
    Root copy = r;
    for (size_t i = 0; i < values.size(); ++i) {
      if (ref.at(copy) == values[i]) return i;
    }
    return 0;
  };
  return o;
}
// A key the loader reads itself (a path, a pose, a list of boxes, a nested block): the
// table names it, so it is allowed and listed, with the type and default the reference shows.
template <class Root>
Option<Root> LoaderOpt(std::string key, std::string type, std::string default_value, std::string description) {
  auto o = BaseOption<Root>(std::move(key), OptionKind::kByLoader, std::move(description));
  o.loader_type = std::move(type), o.loader_default = std::move(default_value);
  return o;
}

namespace option_table_internal {

// The key of an option split into its section path and its last name.
std::pair<std::string, std::string> SplitKey(const std::string& key);
// The node at a dotted section path under `block` (undefined node when absent).
YAML::Node NodeAt(const YAML::Node& block, const std::string& section);
YamlContext ContextAt(const YamlContext& block_ctx, const std::string& section);
// Checks every mapping of the block (its top and each section present) for unknown keys,
// suggesting the nearest allowed key or the section a misplaced key belongs to.
void CheckKeys(const YAML::Node& block, const YamlContext& ctx, const std::vector<std::string>& keys,
               const std::vector<std::string>& aliases);
// The value node of a key, or of its alias (with a warning); throws when both are given.
// `where` is set to the context the value was read from.
YAML::Node FindValue(const YAML::Node& block, const YamlContext& ctx, const std::string& key,
                     const std::string& alias, YamlContext* where, std::vector<std::string>* warnings);
std::string EnumName(const YamlContext& where, const std::string& name, const std::vector<std::string>& names,
                     size_t* index);
std::vector<double> NumberList(const YAML::Node& node, const YamlContext& where, double min, bool min_exclusive,
                               double max);
std::string FormatNumber(double value);
std::string FormatRange(OptionKind kind, double min, double max, bool min_exclusive);

}  // namespace option_table_internal

// Reads the keys of `table` present in `block` (a mapping) into *root; every other key
// of the block is an error naming the file and key, with a suggestion. Keys of kind
// kByLoader are allowed but left to the caller. Returns the warnings (aliases used).
template <class Root>
std::vector<std::string> ReadOptions(const OptionTable<Root>& table, const YAML::Node& block,
                                     const YamlContext& ctx, Root* root) {
  namespace in = option_table_internal;
  std::vector<std::string> keys, aliases, warnings;
  for (const Option<Root>& o : table) {
    if (o.key.find("[]") != std::string::npos) continue;  // keys of list entries: the loader checks them
    keys.push_back(o.key);
    if (!o.alias.empty()) aliases.push_back(o.alias);
  }
  in::CheckKeys(block, ctx, keys, aliases);
  for (const Option<Root>& o : table) {
    if (o.kind == OptionKind::kByLoader) continue;
    YamlContext where;
    const YAML::Node value = in::FindValue(block, ctx, o.key, o.alias, &where, &warnings);
    if (!value) continue;
    switch (o.kind) {
      case OptionKind::kInt:
        o.int_at(*root) = ReadInt(value, where, static_cast<int>(o.min), static_cast<int>(o.max));
        break;
      case OptionKind::kDouble: o.double_at(*root) = ReadDouble(value, where, o.min, o.max); break;
      case OptionKind::kBool: o.bool_at(*root) = ReadBool(value, where); break;
      case OptionKind::kString: o.string_at(*root) = ReadString(value, where); break;
      case OptionKind::kNumberList:
        o.list_at(*root) = in::NumberList(value, where, o.min, o.min_exclusive, o.max);
        break;
      case OptionKind::kEnum: {
        size_t index = 0;
        in::EnumName(where, ReadString(value, where), o.enum_names, &index);
        o.enum_set(*root, index);
        break;
      }
      case OptionKind::kByLoader: break;
    }
  }
  return warnings;
}

// The reference entries of `table`, keys prefixed with `prefix` ("planner."), defaults
// read from `defaults`.
template <class Root>
std::vector<OptionDoc> DocumentOptions(const OptionTable<Root>& table, const std::string& prefix, Root defaults) {
  namespace in = option_table_internal;
  std::vector<OptionDoc> docs;
  for (const Option<Root>& o : table) {
    OptionDoc d;
    d.key = prefix + o.key;
    d.unit = o.unit;
    d.description = o.description;
    d.advanced = o.advanced;
    d.alias = o.alias.empty() ? "" : prefix + o.alias;
    const std::string range = in::FormatRange(o.kind, o.min, o.max, o.min_exclusive);
    switch (o.kind) {
      case OptionKind::kInt:
        d.type = "int in " + range, d.default_value = std::to_string(o.int_at(defaults));
        break;
      case OptionKind::kDouble:
        d.type = "number in " + range, d.default_value = in::FormatNumber(o.double_at(defaults));
        break;
      case OptionKind::kBool: d.type = "bool", d.default_value = o.bool_at(defaults) ? "true" : "false"; break;
      case OptionKind::kString: d.type = "string", d.default_value = "\"" + o.string_at(defaults) + "\""; break;
      case OptionKind::kNumberList: {
        d.type = "list of numbers, each " + range;
        for (double v : o.list_at(defaults)) d.default_value += (d.default_value.empty() ? "" : ", ") + in::FormatNumber(v);
        d.default_value = "[" + d.default_value + "]";
        break;
      }
      case OptionKind::kEnum: {
        d.type = "one of";
        for (size_t i = 0; i < o.enum_names.size(); ++i) d.type += (i ? ", " : " ") + o.enum_names[i];
        d.default_value = o.enum_names[o.enum_get(defaults)];
        break;
      }
      case OptionKind::kByLoader: d.type = o.loader_type, d.default_value = o.loader_default; break;
    }
    docs.push_back(std::move(d));
  }
  return docs;
}

}  // namespace mfp
