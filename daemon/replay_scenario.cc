#include "daemon/replay_scenario.h"

#include <random>

#include "base/check.h"
#include "daemon/daemon_config.h"
#include "io/terrain_yaml.h"
#include "io/yaml_fields.h"
#include "mfp/height_map_t.hpp"
#include "mfp/plan_request_t.hpp"
#include "mfp/terrain_map_t.hpp"

namespace mfp {
namespace {

// Numbers that may be .nan or .inf on purpose (requests that must be rejected).
Eigen::Vector3d ReadTriple(const YAML::Node& node, const YamlContext& ctx) {
  if (!node.IsSequence() || node.size() != 3)
    throw InputError(ctx.Where() + ": expected [x, y, yaw]");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = node[static_cast<size_t>(i)].as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(ctx.Index(static_cast<size_t>(i)).Where() + ": expected a number");
    }
  }
  return v;
}

ScenarioRequest ReadRequest(const YAML::Node& node, const YamlContext& ctx) {
  RejectUnknownKeys(node, ctx,
                    {"at_s", "id", "robot", "start", "start_feet", "legs", "goal", "max_steps",
                     "time_limit_s", "expect", "expect_message"});
  ScenarioRequest r;
  r.at_s = ReadDouble(node["at_s"], ctx.Child("at_s"), 0.0, 3600.0);
  r.id = ReadInt(node["id"], ctx.Child("id"), 0, 2000000000);
  if (auto v = OptionalString(node, ctx, "robot")) r.robot = *v;
  if (node["start"]) r.start_pose = ReadTriple(node["start"], ctx.Child("start"));
  if (node["start_feet"]) {
    const YAML::Node feet = node["start_feet"];
    if (!feet.IsSequence()) throw InputError(ctx.Child("start_feet").Where() + ": expected a list");
    for (size_t i = 0; i < feet.size(); ++i)
      r.start_feet_world_m.push_back(ReadTriple(feet[i], ctx.Child("start_feet").Index(i)));
  }
  if (r.start_pose.has_value() == !r.start_feet_world_m.empty())
    throw InputError(ctx.Where() + ": give exactly one of start and start_feet");
  r.legs = OptionalInt(node, ctx, "legs", 0, 64);
  r.goal = ReadTriple(node["goal"], ctx.Child("goal"));
  if (auto v = OptionalInt(node, ctx, "max_steps", -1000000, 1000000)) r.max_steps = *v;
  if (auto v = OptionalDouble(node, ctx, "time_limit_s", -1e9, 1e9)) r.time_limit_s = *v;
  if (auto v = OptionalString(node, ctx, "expect")) r.expect = *v;
  if (auto v = OptionalString(node, ctx, "expect_message")) r.expect_message = *v;
  return r;
}

}  // namespace

static ReplayScenario LoadReplayScenarioUnguarded(const std::string& path) {
  const YAML::Node root = LoadYamlFile(path);
  const YamlContext ctx{path, ""};
  // mfp-plan's scenario files (config/scenarios) are the likeliest wrong file: say which one is wanted.
  if (root.IsMap() && root["robot"] && root["start"] && root["goal"] && !root["requests"]) {
    throw InputError(path + ": an mfp-plan scenario (robot, start, goal); a replay scenario gives a map (terrain: or "
                            "map:) and timed requests: (daemon/replay_scenario.h; e.g. "
                            "tests/daemon_replay_scenario.yaml)");
  }
  RejectUnknownKeys(root, ctx, {"description", "terrain", "map", "map_at_s", "as_height_map", "requests", "malformed"});
  ReplayScenario s;
  s.file = path;
  if (root["terrain"]) s.terrain = ParseTerrainDescription(root["terrain"], ctx.Child("terrain"));
  if (auto v = OptionalString(root, ctx, "map")) s.map_file = ResolveRelative(path, *v);
  if (s.terrain.has_value() == !s.map_file.empty())
    throw InputError(path + ": give exactly one of terrain and map");
  if (auto v = OptionalDouble(root, ctx, "map_at_s", 0.0, 3600.0)) s.map_at_s = *v;
  s.as_height_map = OptionalBool(root, ctx, "as_height_map").value_or(false);
  if (s.as_height_map && !s.terrain) throw InputError(path + ": as_height_map needs a terrain (boxes)");
  if (const YAML::Node requests = root["requests"]) {
    for (size_t i = 0; i < requests.size(); ++i)
      s.requests.push_back(ReadRequest(requests[i], ctx.Child("requests").Index(i)));
  }
  if (const YAML::Node malformed = root["malformed"]) {
    for (size_t i = 0; i < malformed.size(); ++i) {
      const YamlContext mctx = ctx.Child("malformed").Index(i);
      RejectUnknownKeys(malformed[i], mctx, {"at_s", "channel", "kind"});
      ScenarioMalformed m;
      m.at_s = ReadDouble(malformed[i]["at_s"], mctx.Child("at_s"), 0.0, 3600.0);
      m.channel = ReadString(malformed[i]["channel"], mctx.Child("channel"));
      m.kind = ReadString(malformed[i]["kind"], mctx.Child("kind"));
      MalformedPayload(m.kind, m.channel, 16, 0);  // validates kind and channel
      s.malformed.push_back(m);
    }
  }
  return s;
}

const std::vector<std::string>& MalformedKinds() {
  static const std::vector<std::string> kinds = {"truncated",       "random",    "wrong_fingerprint",
                                                 "negative_length", "oversized", "empty"};
  return kinds;
}

std::vector<uint8_t> MalformedPayload(const std::string& kind, const std::string& channel,
                                      size_t oversize_bytes, uint32_t seed) {
  const bool request = channel == kPlanRequestChannel;
  const bool height_map = channel == kHeightMapChannel;
  if (!request && !height_map && channel != kTerrainMapChannel)
    throw InputError("malformed payload channel '" + channel + "': expected " +
                     kPlanRequestChannel + ", " + kTerrainMapChannel + " or " + kHeightMapChannel);
  auto encode = [](const auto& message) {
    std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
    message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  };
  // A valid message of the channel's type; negative_length writes a length of -1 with
  // no elements (the encoder loops zero times), the payload that aborts LCM's typed
  // subscription.
  const bool negative = kind == "negative_length";
  std::vector<uint8_t> valid;
  if (request) {
    plan_request_t m{};
    m.request_id = 999999;
    m.num_legs = negative ? -1 : 6;
    if (!negative) m.start_feet.assign(6, std::vector<double>(3, 0.0));
    valid = encode(m);
  } else if (height_map) {
    height_map_t m{};
    m.frame = "world";
    m.resolution = 0.02;
    m.nx = negative ? -1 : 4;
    m.ny = 4;
    if (!negative) m.heights.assign(4, std::vector<float>(4, 0.0f));
    valid = encode(m);
  } else {
    terrain_map_t m{};
    m.frame = "world";
    m.num_bytes = negative ? -1 : 64;
    if (!negative) m.data.assign(64, 0x5a);
    valid = encode(m);
  }
  std::mt19937 rng(seed);
  if (kind == "negative_length") return valid;
  if (kind == "truncated") return std::vector<uint8_t>(valid.begin(), valid.begin() + static_cast<long>(valid.size() / 2));
  if (kind == "wrong_fingerprint") {
    valid[0] ^= 0xa5;
    return valid;
  }
  if (kind == "random") {
    std::vector<uint8_t> bytes(16 + rng() % 256);
    for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    return bytes;
  }
  if (kind == "oversized") {
    valid.resize(oversize_bytes, 0);
    return valid;
  }
  if (kind == "empty") return {};
  std::string known;
  for (const std::string& k : MalformedKinds()) known += (known.empty() ? "" : ", ") + k;
  throw InputError("malformed payload kind '" + kind + "': expected one of " + known);
}

ReplayScenario LoadReplayScenario(const std::string& path) {
  return GuardYaml(path, [&] { return LoadReplayScenarioUnguarded(path); });
}

}  // namespace mfp
