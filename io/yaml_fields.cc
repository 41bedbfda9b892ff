#include "io/yaml_fields.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "base/bounded_file.h"
#include "base/check.h"

namespace mfp {

YamlContext YamlContext::Child(const std::string& key) const {
  return {file, path.empty() ? key : path + "." + key};
}

YamlContext YamlContext::Index(size_t i) const {
  return {file, path + "[" + std::to_string(i) + "]"};
}

std::string YamlContext::Where() const {
  return file + (path.empty() ? "" : ": " + path);
}

void RethrowYamlAsInputError(const std::string& file, const YAML::Exception& e) {
  throw InputError(file + ": unexpected YAML shape: " + e.what());
}

YAML::Node LoadYamlFile(const std::string& path) {
  const std::string text = ReadBoundedRegularFile(path, kMaxTextInputBytes, "YAML file");
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(path + ": not valid YAML: " + e.what());
  }
  if (root.IsNull()) {
    throw InputError(path + ": the file is empty (or comments only): expected a mapping of keys (a scenario's, "
                            "robot's or daemon config's keys: docs/options.md, or mfp-plan --list-options)");
  }
  return root;
}

namespace {

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "; did you mean 'x'?" for the allowed key nearest to a typo, "" when none is near.
std::string Suggestion(const std::string& key, const std::vector<std::string>& allowed) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, key.size() / 3) + 1;
  for (const std::string& a : allowed) {
    const size_t d = EditDistance(key, a);
    if (d < best_distance) best = a, best_distance = d;
  }
  return best.empty() ? "" : "; did you mean '" + best + "'?";
}

}  // namespace

void RejectUnknownKeys(const YAML::Node& map, const YamlContext& ctx,
                       const std::vector<std::string>& allowed) {
  if (!map.IsMap()) throw InputError(ctx.Where() + ": expected a mapping");
  const std::set<std::string> ok(allowed.begin(), allowed.end());
  for (const auto& kv : map) {
    // A key may be any node ("? [a, b]\n: 1"); only scalars can name a field.
    if (!kv.first.IsScalar()) {
      throw InputError(ctx.Where() + ": a key is a " +
                       (kv.first.IsSequence() ? std::string("list") : std::string("mapping")) +
                       " (at line " + std::to_string(kv.first.Mark().line + 1) +
                       "); keys must be plain names");
    }
    const std::string key = kv.first.Scalar();
    if (!ok.count(key)) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(ctx.Where() + ": unknown key '" + key + "'" + Suggestion(key, allowed) + " (allowed: " + list +
                       ")");
    }
  }
}

double ReadDouble(const YAML::Node& node, const YamlContext& ctx, double min, double max) {
  double value = 0.0;
  try {
    if (!node.IsScalar()) throw YAML::Exception(YAML::Mark(), "not a scalar");
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(ctx.Where() + ": expected a number");
  }
  if (!std::isfinite(value) || value < min || value > max) {
    std::ostringstream msg;
    msg << ctx.Where() << ": " << value << " is outside the allowed range [" << min << ", "
        << max << "]";
    throw InputError(msg.str());
  }
  return value;
}

int ReadInt(const YAML::Node& node, const YamlContext& ctx, int min, int max) {
  long long value = 0;
  try {
    if (!node.IsScalar()) throw YAML::Exception(YAML::Mark(), "not a scalar");
    value = node.as<long long>();
  } catch (const YAML::Exception&) {
    throw InputError(ctx.Where() + ": expected a whole number");
  }
  if (value < min || value > max) {
    throw InputError(ctx.Where() + ": " + std::to_string(value) +
                     " is outside the allowed range [" + std::to_string(min) + ", " +
                     std::to_string(max) + "]");
  }
  return static_cast<int>(value);
}

bool ReadBool(const YAML::Node& node, const YamlContext& ctx) {
  try {
    if (!node.IsScalar()) throw YAML::Exception(YAML::Mark(), "not a scalar");
    return node.as<bool>();
  } catch (const YAML::Exception&) {
    throw InputError(ctx.Where() + ": expected true or false");
  }
}

std::string ReadString(const YAML::Node& node, const YamlContext& ctx) {
  if (!node.IsScalar()) throw InputError(ctx.Where() + ": expected a string");
  return node.as<std::string>();
}

std::vector<double> ReadNumbers(const YAML::Node& node, const YamlContext& ctx, int size) {
  if (!node.IsSequence()) {
    throw InputError(ctx.Where() + ": expected a list of " +
                     (size < 0 ? std::string("numbers") : std::to_string(size) + " numbers"));
  }
  if (size >= 0 && static_cast<int>(node.size()) != size) {
    throw InputError(ctx.Where() + ": expected " + std::to_string(size) + " numbers, got " +
                     std::to_string(node.size()));
  }
  std::vector<double> out;
  for (size_t i = 0; i < node.size(); ++i) {
    out.push_back(ReadDouble(node[i], ctx.Index(i), -1e9, 1e9));
  }
  return out;
}

std::optional<double> OptionalDouble(const YAML::Node& map, const YamlContext& ctx,
                                     const std::string& key, double min, double max) {
  if (!map[key]) return std::nullopt;
  return ReadDouble(map[key], ctx.Child(key), min, max);
}

std::optional<int> OptionalInt(const YAML::Node& map, const YamlContext& ctx,
                               const std::string& key, int min, int max) {
  if (!map[key]) return std::nullopt;
  return ReadInt(map[key], ctx.Child(key), min, max);
}

std::optional<bool> OptionalBool(const YAML::Node& map, const YamlContext& ctx,
                                 const std::string& key) {
  if (!map[key]) return std::nullopt;
  return ReadBool(map[key], ctx.Child(key));
}

std::optional<std::string> OptionalString(const YAML::Node& map, const YamlContext& ctx,
                                          const std::string& key) {
  if (!map[key]) return std::nullopt;
  return ReadString(map[key], ctx.Child(key));
}

std::string ResolveRelative(const std::string& yaml_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(yaml_file).parent_path() / p).lexically_normal().string();
}

}  // namespace mfp
