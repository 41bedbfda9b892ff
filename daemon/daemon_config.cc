#include "daemon/daemon_config.h"

#include "base/check.h"
#include "io/planner_options_yaml.h"
#include "io/yaml_fields.h"

namespace mfp {
namespace {

using C = DaemonConfig;
using L = DaemonLimits;

template <class T>
Ref<C, T> Limit(T L::*field) {
  return In(&C::limits, field);
}

void AddTopKeys(OptionTable<C>* t) {
  t->push_back(Opt("lcm_url", At(&C::lcm_url), "LCM provider URL (ttl=0 keeps the traffic on this machine)"));
  t->push_back(LoaderOpt<C>("robots", "list of paths", "(required)",
                            "robot YAML or URDF files, relative to this file; requests name them"));
  t->push_back(Opt("default_robot", At(&C::default_robot), "robot planned for when a request names none"));
  t->push_back(LoaderOpt<C>("initial_map", "path", "\"\"", "a map to start with (\"\": none until one arrives)"));
  t->push_back(Opt("heartbeat_period_s", At(&C::heartbeat_period_s), 0.01, 1.0, "period of MFP_STATUS").Unit("s"));
  t->push_back(Opt("lcm_queue_capacity", At(&C::lcm_queue_capacity), 1, 1000000,
                   "messages LCM keeps per channel before it discards").Advanced());
  t->push_back(LoaderOpt<C>("lcm_recv_buf_bytes", "int in [0, 1073741824]", "0",
                            "udpm socket receive buffer (0: limits.max_map_bytes + 1 MiB)")
                   .Unit("bytes").Advanced());
  t->push_back(LoaderOpt<C>("planner", "mapping", "{}",
                            "planner options: the planner.* keys, but time_limit and max_steps are limits.*"));
}

void AddLimitKeys(OptionTable<C>* t) {
  const L d;
  t->push_back(Opt("limits.max_time_limit_s", Limit(&L::max_time_limit_s), 0.01, 3600.0,
                   "requests asking for more time are rejected").Unit("s"));
  t->push_back(Opt("limits.default_time_limit_s", Limit(&L::default_time_limit_s), 0.01, 3600.0,
                   "time of a request that gives none, at most limits.max_time_limit_s (the daemon's planner.time_limit)")
                   .Unit("s"));
  t->push_back(Opt("limits.max_steps", Limit(&L::max_steps), 1, 10000, "requests asking for more steps are rejected"));
  t->push_back(Opt("limits.default_max_steps", Limit(&L::default_max_steps), 0, 10000,
                   "steps of a request that gives none, at most limits.max_steps; 0: 12 x legs "
                   "(the daemon's planner.max_steps)"));
  t->push_back(Opt("limits.queue_size", Limit(&L::queue_size), 1, 1000,
                   "requests waiting; the oldest is dropped beyond"));
  t->push_back(LoaderOpt<C>("limits.max_request_bytes", "int in [64, 16777216]", std::to_string(d.max_request_bytes),
                            "larger plan_request_t payloads are rejected").Unit("bytes"));
  t->push_back(LoaderOpt<C>("limits.max_map_bytes", "int in [64, 1073741824]", std::to_string(d.max_map_bytes),
                            "larger terrain_map_t payloads are rejected").Unit("bytes"));
  t->push_back(Opt("limits.inbox_size", Limit(&L::inbox_size), 1, 1000000,
                   "messages received but not yet decoded; beyond it a request is answered dropped").Advanced());
  t->push_back(Opt("limits.reply_margin_s", Limit(&L::reply_margin_s), 0.0, 1.0,
                   "time kept for the reply: the planner gets the request's time left minus this").Unit("s"));
  t->push_back(Opt("limits.supersede_same_robot", Limit(&L::supersede_same_robot),
                   "a newer request of a robot replaces its older one still queued (answered superseded)"));
  t->push_back(Opt("limits.accept_empty_maps", Limit(&L::accept_empty_maps),
                   "a map without regions replaces a map with regions"));
  t->push_back(Opt("limits.warm_start_plans", Limit(&L::warm_start_plans), 0, 100,
                   "a robot's request starts from this many of the plans last sent to it (0: none)"));
  t->push_back(Opt("limits.max_abandoned_plans", Limit(&L::max_abandoned_plans), 1, 64,
                   "plans answered at their deadline and still stopping, at most; beyond it a request is "
                   "answered dropped (no new planning thread)").Advanced());
  t->push_back(Opt("limits.extraction_threads", Limit(&L::extraction_threads), 1, 64,
                   "threads one map's region extraction runs on (1: the map thread alone)").Advanced());
}

const OptionTable<C>& DaemonOptionTable() {
  static const OptionTable<C> table = [] {
    OptionTable<C> t;
    AddTopKeys(&t);
    AddLimitKeys(&t);
    return t;
  }();
  return table;
}

// Removed keys, with what replaced them.
void RejectRemovedKeys(const YAML::Node& root, const std::string& path) {
  const YAML::Node limits = root["limits"];
  if (limits && limits.IsMap() && limits["start_height_tolerance_m"]) {
    throw InputError(path + ": limits.start_height_tolerance_m was removed: start feet are checked "
                     "once, by the planner, within planner.start_tolerance (metres, default 0.02) of a region");
  }
}

// The daemon's requests take their defaults from limits:, which would silently replace
// the planner's keys of the same meaning: those are refused.
void RejectShadowedPlannerKeys(const YAML::Node& root, const YamlContext& ctx) {
  const YAML::Node planner = root["planner"];
  if (!planner || !planner.IsMap()) return;
  const std::pair<const char*, const char*> kShadowed[] = {{"time_limit", "limits.default_time_limit_s"},
                                                           {"max_steps", "limits.default_max_steps"}};
  for (const auto& [key, winner] : kShadowed) {
    if (planner[key]) {
      throw InputError(ctx.Child("planner").Child(key).Where() + ": the daemon takes " + winner +
                       " instead, which wins: write that");
    }
  }
}

// Sizes in bytes (size_t members) and the ranges that depend on other keys.
void ReadLimitsByLoader(const YAML::Node& node, const YamlContext& ctx, DaemonLimits* limits) {
  if (auto v = OptionalDouble(node, ctx, "default_time_limit_s", 0.01, limits->max_time_limit_s))
    limits->default_time_limit_s = *v;
  if (auto v = OptionalInt(node, ctx, "default_max_steps", 0, limits->max_steps)) limits->default_max_steps = *v;
  if (auto v = OptionalInt(node, ctx, "max_request_bytes", 64, 16 * 1024 * 1024))
    limits->max_request_bytes = static_cast<size_t>(*v);
  if (auto v = OptionalInt(node, ctx, "max_map_bytes", 64, 1024 * 1024 * 1024))
    limits->max_map_bytes = static_cast<size_t>(*v);
}

}  // namespace

static DaemonConfig LoadDaemonConfigUnguarded(const std::string& path) {
  const YAML::Node root = LoadYamlFile(path);
  YamlContext ctx{path, ""};
  if (!root.IsMap()) throw InputError(path + ": expected a mapping at the top level");
  RejectRemovedKeys(root, path);
  DaemonConfig config;
  config.file = path;
  ReadOptions(DaemonOptionTable(), root, ctx, &config);
  if (root["limits"]) ReadLimitsByLoader(root["limits"], ctx.Child("limits"), &config.limits);
  if (config.lcm_url.empty()) throw InputError(ctx.Child("lcm_url").Where() + ": must not be empty");

  const YAML::Node robots = root["robots"];
  if (!robots || !robots.IsSequence() || robots.size() == 0)
    throw InputError(ctx.Child("robots").Where() + ": expected a non-empty list of robot files");
  for (size_t i = 0; i < robots.size(); ++i) {
    config.robot_files.push_back(
        ResolveRelative(path, ReadString(robots[i], ctx.Child("robots").Index(i))));
  }
  if (auto v = OptionalString(root, ctx, "initial_map"); v && !v->empty())
    config.initial_map = ResolveRelative(path, *v);
  if (auto v = OptionalInt(root, ctx, "lcm_recv_buf_bytes", 0, 1 << 30))
    config.lcm_recv_buf_bytes = static_cast<size_t>(*v);
  if (config.lcm_recv_buf_bytes == 0) config.lcm_recv_buf_bytes = config.limits.max_map_bytes + (1u << 20);
  RejectShadowedPlannerKeys(root, ctx);
  if (root["planner"]) config.warnings = ReadPlannerOptions(root["planner"], ctx.Child("planner"), &config.planner);
  // The one source of the requests' defaults (the planner.* keys of these are refused above).
  config.planner.default_time_limit_s = config.limits.default_time_limit_s;
  config.planner.default_max_steps = config.limits.default_max_steps;
  return config;
}

DaemonConfig LoadDaemonConfig(const std::string& path) {
  return GuardYaml(path, [&] { return LoadDaemonConfigUnguarded(path); });
}

std::vector<OptionDoc> DaemonOptionDocs() {
  return DocumentOptions(DaemonOptionTable(), "", DaemonConfig{});
}

}  // namespace mfp
