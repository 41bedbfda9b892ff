#pragma once
// Reading typed, range-checked fields from YAML with errors that name the file, the key
// and the allowed range. The one place config loaders get their error messages from.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace mfp {

// Where a node came from, for messages: "config/robots/hexapod.yaml: legs[2].nominal_offset".
struct YamlContext {
  std::string file;
  std::string path;  // dotted key path of the node
  YamlContext Child(const std::string& key) const;
  YamlContext Index(size_t i) const;
  std::string Where() const;
};

// Loads a YAML file; throws InputError when it is missing, unreadable, malformed or empty
// (no document, or comments only: every caller reads a mapping of keys).
YAML::Node LoadYamlFile(const std::string& path);

// Runs parse(), turning any yaml-cpp exception that escaped the typed readers below (a
// node of an unexpected kind subscripted, an alias cycle, nesting too deep) into an
// InputError naming the file: bad YAML of any shape is an input error, never an abort.
void RethrowYamlAsInputError(const std::string& file, const YAML::Exception& e);
template <typename Parse>
auto GuardYaml(const std::string& file, Parse parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const YAML::Exception& e) {
    RethrowYamlAsInputError(file, e);
    throw;  // not reached
  }
}

// Throws InputError when a mapping has keys other than the allowed ones (catches typos).
void RejectUnknownKeys(const YAML::Node& map, const YamlContext& ctx,
                       const std::vector<std::string>& allowed);

double ReadDouble(const YAML::Node& node, const YamlContext& ctx, double min, double max);
int ReadInt(const YAML::Node& node, const YamlContext& ctx, int min, int max);
bool ReadBool(const YAML::Node& node, const YamlContext& ctx);
std::string ReadString(const YAML::Node& node, const YamlContext& ctx);
// A sequence of exactly `size` finite numbers (size < 0: any length).
std::vector<double> ReadNumbers(const YAML::Node& node, const YamlContext& ctx, int size);

// Optional fields of a mapping: nullopt when the key is absent.
std::optional<double> OptionalDouble(const YAML::Node& map, const YamlContext& ctx,
                                     const std::string& key, double min, double max);
std::optional<int> OptionalInt(const YAML::Node& map, const YamlContext& ctx,
                               const std::string& key, int min, int max);
std::optional<bool> OptionalBool(const YAML::Node& map, const YamlContext& ctx,
                                 const std::string& key);
std::optional<std::string> OptionalString(const YAML::Node& map, const YamlContext& ctx,
                                          const std::string& key);

// Resolves a path written in a YAML file relative to that file's directory.
std::string ResolveRelative(const std::string& yaml_file, const std::string& path);

}  // namespace mfp
