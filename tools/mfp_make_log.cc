// mfp-make-log: writes an LCM log (for lcm-logplayer or mfp-replay) from a scenario
// file: the map on MFP_TERRAIN_MAP, the requests on MFP_PLAN_REQUEST, and malformed
// payloads, at the times the scenario gives (the map as a height_map_t on MFP_HEIGHT_MAP
// with as_height_map). Format: daemon/replay_scenario.h.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "base/check.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_setup.h"
#include "daemon/height_map_message.h"
#include "daemon/map_regions.h"
#include "daemon/replay_scenario.h"
#include "io/cli_parse.h"
#include "io/timestamped_log.h"
#include "lcmtypes/event_log_writer.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/terrain_map_t.hpp"
#include "planner/planning/footstep_planner.h"
#include "terrain/extraction/voxelize.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/height_grid_sampling.h"

namespace mfp {
namespace {

// Logs start at a fixed time so the same scenario always gives the same file.
constexpr int64_t kLogStartUtime = 1700000000000000;

struct Event {
  int64_t utime;
  std::string channel;
  std::vector<uint8_t> bytes;
};

template <class Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  MFP_CHECK(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())) ==
            static_cast<int>(bytes.size()));
  return bytes;
}

int64_t At(double seconds) { return kLogStartUtime + static_cast<int64_t>(std::llround(seconds * 1e6)); }

std::vector<uint8_t> MapBytes(const ReplayScenario& scenario) {
  if (scenario.as_height_map) {
    return Encode(HeightMapMessage(SampleHeightGrid(*scenario.terrain, scenario.terrain->resolution_m),
                                   At(scenario.map_at_s), "world"));
  }
  if (scenario.terrain) return OccupancyMapBytes(VoxelizeTerrain(*scenario.terrain), true);
  std::ifstream in(scenario.map_file, std::ios::binary);
  if (!in) throw InputError(scenario.file + ": map: cannot open '" + scenario.map_file + "'");
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

int Run(const std::string& scenario_path, const std::string& config_path, const std::string& out) {
  const ReplayScenario scenario = LoadReplayScenario(scenario_path);
  const DaemonSetup setup = LoadDaemonSetup(LoadDaemonConfig(config_path));
  const std::vector<uint8_t> map_bytes = MapBytes(scenario);
  // The regions the daemon will extract, to put start stances on the surface.
  const std::vector<ConvexRegion> regions = MakeOctomapMapFunction(setup)(
      std::string(map_bytes.begin(), map_bytes.end()), scenario.as_height_map ? kHeightMapFormat : "bt",
      scenario.file + ": map").regions;

  std::vector<Event> events;
  terrain_map_t map{};
  map.utime = At(scenario.map_at_s);
  map.frame = "world";
  map.format = scenario.map_file.empty() ? "bt" : scenario.map_file.substr(scenario.map_file.rfind('.') + 1);
  map.data = map_bytes;
  map.num_bytes = static_cast<int32_t>(map.data.size());
  if (scenario.as_height_map) {
    events.push_back({map.utime, kHeightMapChannel, map_bytes});  // already a height_map_t
  } else {
    events.push_back({map.utime, kTerrainMapChannel, Encode(map)});
  }

  for (const ScenarioRequest& r : scenario.requests) {
    const std::string robot_name = r.robot.empty() ? setup.config.default_robot : r.robot;
    plan_request_t m{};
    m.utime = At(r.at_s);
    m.request_id = r.id;
    m.robot = r.robot;
    std::vector<Eigen::Vector3d> feet = r.start_feet_world_m;
    if (r.start_pose) {
      const auto robot = setup.robots.find(robot_name);
      if (robot == setup.robots.end())
        throw InputError(scenario.file + ": request " + std::to_string(r.id) +
                         ": start pose needs a configured robot, not '" + robot_name + "'");
      feet = NominalStance(robot->second, regions, r.start_pose->x(), r.start_pose->y(),
                           r.start_pose->z());
    }
    if (r.legs) feet.resize(static_cast<size_t>(*r.legs), Eigen::Vector3d::Zero());
    for (const Eigen::Vector3d& f : feet) m.start_feet.push_back({f.x(), f.y(), f.z()});
    m.num_legs = static_cast<int32_t>(m.start_feet.size());
    m.goal_x = r.goal.x();
    m.goal_y = r.goal.y();
    m.goal_yaw = r.goal.z();
    m.max_steps = r.max_steps;
    m.time_limit_s = r.time_limit_s;
    events.push_back({m.utime, kPlanRequestChannel, Encode(m)});
  }
  uint32_t seed = 1;
  for (const ScenarioMalformed& m : scenario.malformed) {
    const size_t oversize = (m.channel == kPlanRequestChannel ? setup.config.limits.max_request_bytes
                                                              : setup.config.limits.max_map_bytes) + 1;
    events.push_back({At(m.at_s), m.channel, MalformedPayload(m.kind, m.channel, oversize, seed++)});
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.utime < b.utime; });

  EventLogWriter writer(out);
  for (const Event& e : events) {
    if (!writer.Write(e.channel, e.bytes.data(), e.bytes.size(), e.utime))
      throw InputError("cannot write to '" + out + "'");
  }
  LogLine("mfp-make-log", "wrote " + std::to_string(events.size()) + " events (" +
                              std::to_string(regions.size()) + " regions in the map, " +
                              std::to_string(scenario.requests.size()) + " requests, " +
                              std::to_string(scenario.malformed.size()) + " malformed) to " + out);
  return 0;
}

}  // namespace
}  // namespace mfp

int main(int argc, char** argv) {
  CLI::App app{"mfp-make-log: an LCM log of a map and requests from a scenario file"};
  std::string scenario, config = "config/daemon.yaml", out;
  app.add_option("scenario", scenario, "scenario YAML (daemon/replay_scenario.h)")->required();
  app.add_option("--config", config, "daemon YAML: robots and limits")->capture_default_str();
  app.add_option("--out", out, "LCM log to write")->required();
  MFP_CLI_PARSE(app, argc, argv);
  try {
    return mfp::Run(scenario, config, out);
  } catch (const mfp::InputError& e) {
    mfp::LogLine("mfp-make-log", std::string("error: ") + e.what());
    return 2;
  }
}
