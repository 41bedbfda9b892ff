// mfp-replay: runs the daemon's handlers over an LCM log, offline, for debugging. Reads
// the log through LCM's file:// provider as fast as possible; each event is handled
// to completion (a request is planned before the next event is read) and stamped with
// the log's time, so a replay does not depend on the machine's speed: the same log
// gives the same replies (up to solve times, and plans cut by a time limit). Writes the
// input events and the daemon's outputs (MFP_REGIONS, MFP_PLAN, MFP_STATUS every
// heartbeat period of log time) to an LCM log.
#include <CLI/CLI.hpp>

#include "base/check.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_core.h"
#include "daemon/daemon_setup.h"
#include "daemon/map_regions.h"
#include "daemon/solver_plan_function.h"
#include "io/cli_parse.h"
#include "io/timestamped_log.h"
#include "lcmtypes/event_log_reader.h"
#include "lcmtypes/event_log_writer.h"
#include "lcmtypes/transport.h"

namespace mfp {
namespace {

constexpr const char* kProgram = "mfp-replay";

int Run(const std::string& log_path, const std::string& out_path, const std::string& config_path,
        bool verbose) {
  auto setup = std::make_shared<const DaemonSetup>(LoadDaemonSetup(LoadDaemonConfig(config_path)));
  // The largest event the daemon would accept (larger ones could only be rejected).
  EventLogReader input(log_path, std::max(setup->config.limits.max_map_bytes,
                                          setup->config.limits.max_request_bytes));
  EventLogWriter output(out_path);

  int64_t log_utime = 0;
  auto log = [verbose](const std::string& line) {
    if (verbose) LogLine(kProgram, line);
  };
  DaemonCore core(setup, MakeOctomapMapFunction(*setup), MakeSolverPlanFunction(), output,
                  [&log_utime] { return log_utime; }, log);
  const auto heartbeat_us = static_cast<int64_t>(setup->config.heartbeat_period_s * 1e6);
  int64_t next_heartbeat = -1;
  int64_t events = 0;
  auto handle = [&](const RawMessage& message) {
    ++events;
    log_utime = message.receive_utime;
    output.SetTime(log_utime);
    if (next_heartbeat < 0) next_heartbeat = log_utime;
    while (log_utime >= next_heartbeat) {
      core.PublishStatus();
      next_heartbeat += heartbeat_us;
    }
    output.Write(message.channel, message.data, message.size, log_utime);
    core.OnMessage(message);
    while (core.PlanNext()) {
    }
  };
  LogEvent event;
  while (input.Next(&event)) {
    if (event.channel != kTerrainMapChannel && event.channel != kPlanRequestChannel) continue;
    handle(RawMessage{event.channel, event.data.data(), event.data.size(), event.utime});
  }
  core.PublishStatus();
  const DaemonCounters c = core.counters();
  LogLine(kProgram, "replayed " + std::to_string(events) + " events: requests " +
                        std::to_string(c.requests) + ", plans " + std::to_string(c.plans) +
                        ", rejected messages " + std::to_string(c.rejected_messages) + ", maps " +
                        std::to_string(c.maps) + "; wrote " + out_path);
  return 0;
}

}  // namespace
}  // namespace mfp

int main(int argc, char** argv) {
  CLI::App app{"mfp-replay: the daemon's handlers over an LCM log, deterministically"};
  std::string log, out, config = "config/daemon.yaml";
  bool verbose = false;
  app.add_option("log", log, "input LCM log (MFP_TERRAIN_MAP, MFP_PLAN_REQUEST)")->required();
  app.add_option("--out", out, "output LCM log")->required();
  app.add_option("--config", config, "daemon YAML")->capture_default_str();
  app.add_flag("-v,--verbose", verbose, "log every map, request and plan");
  MFP_CLI_PARSE(app, argc, argv);
  try {
    return mfp::Run(log, out, config, verbose);
  } catch (const mfp::InputError& e) {
    mfp::LogLine("mfp-replay", std::string("error: ") + e.what());
    return 2;
  }
}
