#include "tools/daemon/daemon_config.h"

#include "planner/base/check.h"
#include "planner/base/yaml_fields.h"
#include "planner/io/planner_options_yaml.h"

namespace mfp {
namespace {

void ReadLimits(const YAML::Node& node, const YamlContext& ctx, DaemonLimits* limits) {
  RejectUnknownKeys(node, ctx,
                    {"default_time_limit_s", "max_time_limit_s", "default_max_steps",
                     "max_steps", "queue_size", "max_request_bytes", "max_map_bytes",
                     "start_height_tolerance_m", "inbox_size", "reply_margin_s",
                     "supersede_same_robot", "accept_empty_maps",
                     "warm_start_plans"});
  // Removed: one check of the start feet, the planner's (request_check.h).
  if (node["start_height_tolerance_m"]) {
    throw InputError(ctx.file + ": limits.start_height_tolerance_m was removed: start feet are checked "
                     "once, by the planner, within planner.start_tolerance (metres, default 0.02) of a region");
  }
  if (auto v = OptionalDouble(node, ctx, "max_time_limit_s", 0.01, 3600.0))
    limits->max_time_limit_s = *v;
  if (auto v = OptionalDouble(node, ctx, "default_time_limit_s", 0.01, limits->max_time_limit_s))
    limits->default_time_limit_s = *v;
  if (auto v = OptionalInt(node, ctx, "max_steps", 1, 10000)) limits->max_steps = *v;
  if (auto v = OptionalInt(node, ctx, "default_max_steps", 0, limits->max_steps))
    limits->default_max_steps = *v;
  if (auto v = OptionalInt(node, ctx, "queue_size", 1, 1000)) limits->queue_size = *v;
  if (auto v = OptionalInt(node, ctx, "max_request_bytes", 64, 16 * 1024 * 1024))
    limits->max_request_bytes = static_cast<size_t>(*v);
  if (auto v = OptionalInt(node, ctx, "max_map_bytes", 64, 1024 * 1024 * 1024))
    limits->max_map_bytes = static_cast<size_t>(*v);
  if (auto v = OptionalInt(node, ctx, "inbox_size", 1, 1000000)) limits->inbox_size = *v;
  if (auto v = OptionalDouble(node, ctx, "reply_margin_s", 0.0, 1.0)) limits->reply_margin_s = *v;
  if (auto v = OptionalBool(node, ctx, "supersede_same_robot")) limits->supersede_same_robot = *v;
  if (auto v = OptionalInt(node, ctx, "warm_start_plans", 0, 100)) limits->warm_start_plans = *v;
  if (auto v = OptionalBool(node, ctx, "accept_empty_maps")) limits->accept_empty_maps = *v;
}

}  // namespace

static DaemonConfig LoadDaemonConfigUnguarded(const std::string& path) {
  const YAML::Node root = LoadYamlFile(path);
  YamlContext ctx{path, ""};
  if (!root.IsMap()) throw InputError(path + ": expected a mapping at the top level");
  RejectUnknownKeys(root, ctx,
                    {"lcm_url", "robots", "default_robot", "initial_map",
                     "heartbeat_period_s", "lcm_queue_capacity", "lcm_recv_buf_bytes", "limits",
                     "planner"});
  DaemonConfig config;
  config.file = path;
  if (auto v = OptionalString(root, ctx, "lcm_url")) config.lcm_url = *v;
  if (config.lcm_url.empty()) throw InputError(ctx.Child("lcm_url").Where() + ": must not be empty");

  const YAML::Node robots = root["robots"];
  if (!robots || !robots.IsSequence() || robots.size() == 0)
    throw InputError(ctx.Child("robots").Where() + ": expected a non-empty list of robot files");
  for (size_t i = 0; i < robots.size(); ++i) {
    config.robot_files.push_back(
        ResolveRelative(path, ReadString(robots[i], ctx.Child("robots").Index(i))));
  }
  if (auto v = OptionalString(root, ctx, "default_robot")) config.default_robot = *v;
  if (auto v = OptionalString(root, ctx, "initial_map"); v && !v->empty())
    config.initial_map = ResolveRelative(path, *v);
  if (auto v = OptionalDouble(root, ctx, "heartbeat_period_s", 0.01, 1.0))
    config.heartbeat_period_s = *v;
  if (auto v = OptionalInt(root, ctx, "lcm_queue_capacity", 1, 1000000))
    config.lcm_queue_capacity = *v;
  if (auto v = OptionalInt(root, ctx, "lcm_recv_buf_bytes", 0, 1 << 30))
    config.lcm_recv_buf_bytes = static_cast<size_t>(*v);
  if (root["limits"]) ReadLimits(root["limits"], ctx.Child("limits"), &config.limits);
  if (config.lcm_recv_buf_bytes == 0) config.lcm_recv_buf_bytes = config.limits.max_map_bytes + (1u << 20);
  if (root["planner"]) ReadPlannerOptions(root["planner"], ctx.Child("planner"), &config.planner);
  config.planner.default_time_limit_s = config.limits.default_time_limit_s;
  config.planner.default_max_steps = config.limits.default_max_steps;
  return config;
}

DaemonConfig LoadDaemonConfig(const std::string& path) {
  return GuardYaml(path, [&] { return LoadDaemonConfigUnguarded(path); });
}

}  // namespace mfp
