// mfp-daemon: the long-running onboard planner. Subscribes to MFP_TERRAIN_MAP and
// MFP_PLAN_REQUEST, publishes MFP_REGIONS after each map, one MFP_PLAN per request and
// MFP_STATUS as a heartbeat. SIGINT/SIGTERM stop it (exit 0), SIGHUP reloads the config.
#include <CLI/CLI.hpp>
#include <csignal>
#include <memory>
#include <string>

#include "lcmtypes/lcm_transport.h"
#include "planner/base/check.h"
#include "tools/daemon/daemon_config.h"
#include "tools/daemon/daemon_core.h"
#include "tools/daemon/daemon_runner.h"
#include "tools/daemon/daemon_setup.h"
#include "tools/daemon/solver_plan_function.h"
#include "tools/daemon/map_regions.h"
#include "tools/daemon/timestamped_log.h"

namespace {

constexpr const char* kProgram = "mfp-daemon";

void Log(const std::string& text) { mfp::LogLine(kProgram, text); }

std::shared_ptr<const mfp::DaemonSetup> LoadSetup(const std::string& config_path,
                                                  const std::string& url_override) {
  mfp::DaemonConfig config = mfp::LoadDaemonConfig(config_path);
  if (!url_override.empty()) config.lcm_url = url_override;
  return std::make_shared<const mfp::DaemonSetup>(mfp::LoadDaemonSetup(config));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mfp-daemon: footstep plans over LCM"};
  std::string config_path;
  std::string url_override;
  app.add_option("--config", config_path, "daemon YAML (config/daemon.yaml)")->required();
  app.add_option("--lcm-url", url_override, "LCM provider URL; overrides the config's lcm_url");
  CLI11_PARSE(app, argc, argv);

  // Block the signals in every thread; the main thread takes them with sigwait.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  std::shared_ptr<const mfp::DaemonSetup> setup;
  std::unique_ptr<mfp::LcmTransport> transport;
  try {
    setup = LoadSetup(config_path, url_override);
    transport = std::make_unique<mfp::LcmTransport>(setup->config.lcm_url);
  } catch (const mfp::InputError& e) {
    Log(std::string("error: ") + e.what());
    return 2;
  }

  mfp::DaemonCore core(setup, mfp::MakeOctomapMapFunction(*setup), mfp::MakeSolverPlanFunction(),
                       *transport, &mfp::WallUtime, &Log);
  core.SubscribeTo(*transport);
  if (!setup->config.initial_map.empty()) {
    try {
      core.LoadMapFile(setup->config.initial_map);
    } catch (const mfp::InputError& e) {
      Log(std::string("error: ") + e.what());
      return 2;
    }
  }
  std::string robots;
  for (const auto& entry : setup->robots) robots += (robots.empty() ? "" : ", ") + entry.first;
  Log("started: lcm " + setup->config.lcm_url + ", robots " + robots + " (default " +
      setup->config.default_robot + ")");

  mfp::DaemonRunner runner(core, *transport, setup->config.heartbeat_period_s);
  for (;;) {
    int signal_number = 0;
    if (sigwait(&signals, &signal_number) != 0) continue;
    if (signal_number == SIGHUP) {
      try {
        auto reloaded = LoadSetup(config_path, url_override);
        if (reloaded->config.lcm_url != setup->config.lcm_url)
          Log("lcm_url changed in the config; it takes effect on restart");
        if (reloaded->config.initial_map != setup->config.initial_map)
          Log("initial_map changed in the config; it is read on restart");
        core.Reconfigure(reloaded, mfp::MakeOctomapMapFunction(*reloaded));
        runner.SetHeartbeatPeriod(reloaded->config.heartbeat_period_s);
        setup = reloaded;
        Log("SIGHUP: configuration reloaded from " + config_path);
      } catch (const mfp::InputError& e) {
        Log(std::string("SIGHUP: reload failed, keeping the previous configuration: ") + e.what());
      }
      continue;
    }
    Log(std::string(signal_number == SIGINT ? "SIGINT" : "SIGTERM") + ": stopping");
    break;
  }
  runner.Stop();
  const mfp::DaemonCounters c = core.counters();
  Log("stopped: requests " + std::to_string(c.requests) + ", plans " + std::to_string(c.plans) +
      ", rejected messages " + std::to_string(c.rejected_messages));
  return 0;
}
