// mfp-daemon: the long-running onboard planner. Subscribes to MFP_TERRAIN_MAP and
// MFP_PLAN_REQUEST, publishes MFP_REGIONS after each map, one MFP_PLAN per request and
// MFP_STATUS as a heartbeat. SIGINT/SIGTERM stop it (exit 0), SIGHUP reloads the config.
#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/check.h"
#include "daemon/abandonable_task.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_core.h"
#include "daemon/daemon_runner.h"
#include "daemon/daemon_setup.h"
#include "daemon/heap_release.h"
#include "daemon/map_regions.h"
#include "daemon/solver_plan_function.h"
#include "daemon/udp_counters.h"
#include "io/cli_parse.h"
#include "io/timestamped_log.h"
#include "lcmtypes/lcm_transport.h"

namespace {

constexpr const char* kProgram = "mfp-daemon";

void Log(const std::string& text) { mfp::LogLine(kProgram, text); }

std::shared_ptr<const mfp::DaemonSetup> LoadSetup(const std::string& config_path,
                                                  const std::string& url_override) {
  mfp::DaemonConfig config = mfp::LoadDaemonConfig(config_path);
  for (const std::string& warning : config.warnings) Log("warning: " + warning);
  if (!url_override.empty()) config.lcm_url = url_override;
  return std::make_shared<const mfp::DaemonSetup>(mfp::LoadDaemonSetup(config));
}

// A reload loads robots on a thread of its own (a hostile robot may take seconds to
// derive) while the main thread keeps taking signals: SIGTERM during a reload stops the
// daemon at once and leaves the reload to end unobserved.
using ReloadTask = mfp::AbandonableTask<std::shared_ptr<const mfp::DaemonSetup>>;

void ApplyReload(const std::shared_ptr<const mfp::DaemonSetup>& reloaded, const std::string& config_path,
                 std::shared_ptr<const mfp::DaemonSetup>& setup, mfp::DaemonCore& core, mfp::DaemonRunner& runner) {
  if (reloaded->config.lcm_url != setup->config.lcm_url ||
      reloaded->config.lcm_queue_capacity != setup->config.lcm_queue_capacity ||
      reloaded->config.lcm_recv_buf_bytes != setup->config.lcm_recv_buf_bytes)
    Log("lcm_url, lcm_queue_capacity or lcm_recv_buf_bytes changed in the config; "
        "they take effect on restart");
  if (reloaded->config.initial_map != setup->config.initial_map)
    Log("initial_map changed in the config; it is read on restart");
  core.Reconfigure(reloaded, mfp::MakeOctomapMapFunction(*reloaded));
  runner.SetHeartbeatPeriod(reloaded->config.heartbeat_period_s);
  setup = reloaded;
  Log("SIGHUP: configuration reloaded from " + config_path);
}

// Exit 0 at once: a plan, an extraction or start-up work abandoned by a stop may still run
// on its detached thread, so no destructors run under it.
[[noreturn]] void ExitLeavingThreads() {
  std::fflush(nullptr);
  std::_Exit(0);
}

// Start-up work (deriving the robots, reading initial_map) on a thread of its own while
// the main thread takes signals: SIGINT or SIGTERM meanwhile answer nullopt at once (the
// caller exits; the work is left to end unobserved), SIGHUP is logged and ignored.
// Rethrows what the work throws.
template <class Result>
std::optional<Result> WhileTakingSignals(const sigset_t& signals, std::function<Result()> work,
                                         const std::string& what) {
  mfp::AbandonableTask<Result> task(std::move(work));
  const std::atomic<bool> never{false};
  for (;;) {
    std::optional<Result> done = task.Wait(std::chrono::steady_clock::now() + std::chrono::milliseconds(50), never);
    if (done) return done;
    const timespec no_wait{0, 0};
    const int signal_number = sigtimedwait(&signals, nullptr, &no_wait);
    if (signal_number == SIGHUP) Log("SIGHUP during start-up (" + what + ") ignored: send it once started");
    if (signal_number == SIGINT || signal_number == SIGTERM) {
      Log(std::string(signal_number == SIGINT ? "SIGINT" : "SIGTERM") + ": stopping during start-up (" + what +
          " abandoned)");
      return std::nullopt;
    }
  }
}

// Takes signals until SIGINT or SIGTERM (checked every 50 ms), reloading on SIGHUP.
void ServeSignals(const sigset_t& signals, const std::string& config_path, const std::string& url_override,
                  std::shared_ptr<const mfp::DaemonSetup>& setup, mfp::DaemonCore& core,
                  mfp::DaemonRunner& runner) {
  const std::atomic<bool> never{false};
  std::unique_ptr<ReloadTask> reload;
  for (;;) {
    if (reload) {
      try {
        std::optional<std::shared_ptr<const mfp::DaemonSetup>> done =
            reload->Wait(std::chrono::steady_clock::now(), never);
        if (done) {
          reload.reset();
          ApplyReload(*done, config_path, setup, core, runner);
        }
      } catch (const std::exception& e) {
        // InputError for bad files; anything else a reader let escape is no reason to
        // drop a working configuration either.
        reload.reset();
        Log(std::string("SIGHUP: reload failed, keeping the previous configuration: ") + e.what());
      }
    }
    const timespec poll{0, 50 * 1000 * 1000};
    const int signal_number = sigtimedwait(&signals, nullptr, &poll);
    if (signal_number < 0) continue;  // timeout or EINTR
    if (signal_number == SIGHUP) {
      if (reload) {
        Log("SIGHUP: a reload is still loading; send SIGHUP again once it is done");
        continue;
      }
      try {
        reload = std::make_unique<ReloadTask>([config_path, url_override] {
          return LoadSetup(config_path, url_override);
        });
        Log("SIGHUP: reloading " + config_path);
      } catch (const std::exception& e) {
        Log(std::string("SIGHUP: reload not started (no thread), keeping the configuration: ") + e.what());
      }
      continue;
    }
    Log(std::string(signal_number == SIGINT ? "SIGINT" : "SIGTERM") + ": stopping" +
        (reload ? " (the reload in progress is abandoned)" : ""));
    return;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mfp-daemon: footstep plans over LCM"};
  std::string config_path;
  std::string url_override;
  app.add_option("--config", config_path, "daemon YAML (config/daemon.yaml)")->required();
  app.add_option("--lcm-url", url_override, "LCM provider URL; overrides the config's lcm_url");
  MFP_CLI_PARSE(app, argc, argv);

  // Block the signals in every thread; the main thread takes them with sigwait.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  mfp::BoundHeapRetention();

  std::shared_ptr<const mfp::DaemonSetup> setup;
  std::unique_ptr<mfp::LcmTransport> transport;
  try {
    std::optional<std::shared_ptr<const mfp::DaemonSetup>> loaded =
        WhileTakingSignals<std::shared_ptr<const mfp::DaemonSetup>>(
            signals, [config_path, url_override] { return LoadSetup(config_path, url_override); },
            "loading the configuration and deriving its robots");
    if (!loaded) ExitLeavingThreads();
    setup = std::move(*loaded);
    const std::string url =
        mfp::WithReceiveBuffer(setup->config.lcm_url, setup->config.lcm_recv_buf_bytes);
    transport = std::make_unique<mfp::LcmTransport>(url, setup->config.lcm_queue_capacity);
    if (url.rfind("udpm://", 0) == 0) {
      const int64_t rmem_max = mfp::ReadRmemMax();
      if (rmem_max >= 0 && static_cast<size_t>(rmem_max) < setup->config.lcm_recv_buf_bytes)
        Log("warning: the kernel caps socket receive buffers at " + std::to_string(rmem_max) +
            " bytes (net.core.rmem_max), below lcm_recv_buf_bytes = " +
            std::to_string(setup->config.lcm_recv_buf_bytes) +
            ": large maps may be lost; raise it with sysctl -w net.core.rmem_max=" +
            std::to_string(setup->config.lcm_recv_buf_bytes));
    }
  } catch (const mfp::InputError& e) {
    Log(std::string("error: ") + e.what());
    return 2;
  }

  mfp::DaemonCore core(setup, mfp::MakeOctomapMapFunction(*setup), mfp::MakeSolverPlanFunction(),
                       *transport, &mfp::WallUtime, &Log);
  core.SubscribeTo(*transport);
  if (setup->config.lcm_url.rfind("udpm://", 0) == 0) {
    const int64_t udp_errors_at_start = mfp::ReadUdpReceiveErrors();
    core.SetUdpErrorSource([udp_errors_at_start] {
      const int64_t now = mfp::ReadUdpReceiveErrors();
      return now < 0 || udp_errors_at_start < 0 ? -1 : now - udp_errors_at_start;
    });
  }
  if (!setup->config.initial_map.empty()) {
    try {
      const std::string path = setup->config.initial_map;
      const std::optional<bool> read = WhileTakingSignals<bool>(
          signals, [&core, path] { core.LoadMapFile(path); return true; }, "reading initial_map " + path);
      if (!read) ExitLeavingThreads();
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
  ServeSignals(signals, config_path, url_override, setup, core, runner);
  runner.Stop();
  const mfp::DaemonCounters c = core.counters();
  Log("stopped: requests " + std::to_string(c.requests) + ", plans " + std::to_string(c.plans) +
      ", rejected messages " + std::to_string(c.rejected_messages) + ", dropped " +
      std::to_string(c.dropped_requests) + ", abandoned solves " +
      std::to_string(c.abandoned_solves));
  ExitLeavingThreads();
}
