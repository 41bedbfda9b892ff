// mfp-daemon-bench: the daemon in-process over memq:// with the real planner and the
// real map pipeline, driven like a robot would drive it.
//  1. Latency: 12-step hexapod requests at 10 Hz; request-to-plan latency (publish of
//     the request to receipt of its plan_t) for planned requests, median and p99, plus
//     how many were dropped by the bounded queue and the planner's own solve times.
//  2. Memory: 10,000 requests (default) pushed through decode, validation and the queue
//     as fast as they can be published while the worker plans what it can; the
//     process's resident memory (VmRSS) before, during and after. Most of these are
//     dropped (answered) by the newest-first queue: this measures that nothing grows
//     with the number of requests, not 10,000 solves.
// Prints a table; timing is never a pass/fail criterion.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

#include "lcmtypes/lcm_transport.h"
#include "lcmtypes/message_guard.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/plan_t.hpp"
#include "mfp/terrain_map_t.hpp"
#include "planner/base/check.h"
#include "terrain/octomap_io.h"
#include "terrain/voxelize.h"
#include "tools/daemon/daemon_config.h"
#include "tools/daemon/daemon_core.h"
#include "tools/daemon/daemon_runner.h"
#include "tools/daemon/daemon_setup.h"
#include "tools/daemon/solver_plan_function.h"
#include "tools/daemon/map_regions.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

double RssMiB() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      double kib = 0;
      in >> kib;
      return kib / 1024.0;
    }
    std::getline(in, key);
  }
  return -1;
}

int64_t NowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(Clock::now().time_since_epoch()).count();
}

template <class Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double rank = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<size_t>(std::floor(rank));
  const auto hi = std::min(v.size() - 1, lo + 1);
  return v[lo] + (rank - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

// Replies by request id, with their receive time.
class ReplyLog {
 public:
  void Add(const plan_t& p) {
    std::lock_guard<std::mutex> lock(mutex_);
    replies_[p.request_id] = {NowUs(), p.status, p.solve_time_s};
    changed_.notify_all();
  }
  bool WaitFor(size_t count, std::chrono::seconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return replies_.size() >= count; });
  }
  struct Reply {
    int64_t receive_us;
    int8_t status;
    double solve_time_s;
  };
  std::map<int64_t, Reply> Snapshot() {
    std::lock_guard<std::mutex> lock(mutex_);
    return replies_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<int64_t, Reply> replies_;
};

int Run(const std::string& config_path, int latency_requests, double rate_hz, int memory_requests,
        double time_limit_s) {
  DaemonConfig config = LoadDaemonConfig(config_path);
  auto setup = std::make_shared<const DaemonSetup>(LoadDaemonSetup(config));
  const RobotModel& hexapod = setup->robots.at("hexapod");

  // Flat ground, 4 m x 3 m, as an OctoMap through the daemon's own map pipeline.
  TerrainDescription terrain;
  TerrainBox ground;
  ground.name = "ground";
  ground.center_world_m = Eigen::Vector3d(1.0, 0.0, -0.05);
  ground.size_m = Eigen::Vector3d(4.0, 3.0, 0.1);
  terrain.boxes.push_back(ground);
  terrain_map_t map{};
  map.utime = NowUs();
  map.frame = "world";
  map.format = "bt";
  map.data = OccupancyMapBytes(VoxelizeTerrain(terrain), true);
  map.num_bytes = static_cast<int32_t>(map.data.size());

  LcmTransport transport("memq://");
  DaemonCore core(setup, MakeOctomapMapFunction(*setup), MakeSolverPlanFunction(), transport, &NowUs);
  core.SubscribeTo(transport);
  ReplyLog replies;
  transport.Subscribe(kPlanChannel, [&](const RawMessage& raw) {
    plan_t p;
    if (DecodeGuarded(raw.data, raw.size, 1 << 24, &p).empty()) replies.Add(p);
  });
  const double rss_start = RssMiB();
  DaemonRunner runner(core, transport, setup->config.heartbeat_period_s);
  const auto map_bytes = Encode(map);
  transport.Publish(kTerrainMapChannel, map_bytes.data(), map_bytes.size());
  while (core.counters().maps == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));

  // Nominal hexapod stance at the origin; 12 new footsteps towards a goal 0.25 m ahead.
  plan_request_t request{};
  request.num_legs = hexapod.num_legs();
  for (const LegModel& leg : hexapod.legs)
    request.start_feet.push_back({leg.nominal_offset_body_m.x(), leg.nominal_offset_body_m.y(), 0.0});
  request.goal_x = 0.25;
  request.max_steps = 12;
  request.time_limit_s = time_limit_s;

  // 1. Latency at rate_hz.
  std::map<int64_t, int64_t> sent_us;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  auto next = Clock::now();
  for (int i = 0; i < latency_requests; ++i) {
    std::this_thread::sleep_until(next);
    next += period;
    request.request_id = i + 1;
    request.utime = NowUs();
    const auto bytes = Encode(request);
    sent_us[request.request_id] = NowUs();
    transport.Publish(kPlanRequestChannel, bytes.data(), bytes.size());
  }
  replies.WaitFor(static_cast<size_t>(latency_requests), std::chrono::seconds(600));
  std::vector<double> latency_ms, solve_ms;
  std::map<std::string, int> statuses;
  for (const auto& [id, reply] : replies.Snapshot()) {
    if (sent_us.count(id) == 0) continue;
    const auto status = static_cast<SolveStatus>(reply.status);
    ++statuses[ToString(status)];
    if (HasPlan(status)) {
      latency_ms.push_back(1e-3 * static_cast<double>(reply.receive_us - sent_us[id]));
      solve_ms.push_back(1e3 * reply.solve_time_s);
    }
  }
  std::printf("mfp-daemon-bench: in-process daemon over memq://, real planner (default relaxation backend), real map pipeline\n");
  std::printf("  hexapod, 12 new footsteps per request, goal 0.25 m ahead, time limit %.1f s, queue %d\n",
              time_limit_s, setup->config.limits.queue_size);
  std::printf("\n1. latency: %d requests at %.1f Hz\n", latency_requests, rate_hz);
  std::printf("   %-34s %10s\n", "replies by status", "count");
  for (const auto& [name, count] : statuses) std::printf("   %-34s %10d\n", name.c_str(), count);
  std::printf("   %-34s %10s %10s %10s\n", "[ms]", "median", "p99", "max");
  std::printf("   %-34s %10.1f %10.1f %10.1f\n", "request-to-plan latency (planned)", Percentile(latency_ms, 0.5),
              Percentile(latency_ms, 0.99), Percentile(latency_ms, 1.0));
  std::printf("   %-34s %10.1f %10.1f %10.1f\n", "planner solve time", Percentile(solve_ms, 0.5),
              Percentile(solve_ms, 0.99), Percentile(solve_ms, 1.0));

  // 2. Memory over many requests.
  const double rss_before = RssMiB();
  std::printf("\n2. memory: %d requests published back to back (ids from 1000001)\n", memory_requests);
  std::printf("   %-12s %10s %10s %10s %10s\n", "requests", "VmRSS MiB", "replies", "planned*", "dropped");
  std::printf("   %-12s %10.1f\n", "before", rss_before);
  const int64_t first_id = 1000001;
  for (int i = 0; i < memory_requests; ++i) {
    request.request_id = first_id + i;
    request.utime = NowUs();
    const auto bytes = Encode(request);
    transport.Publish(kPlanRequestChannel, bytes.data(), bytes.size());
    // memq queues every message until the receive thread handles it: pace the
    // publisher so the test measures the daemon, not an unbounded memq backlog.
    if (i % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if ((i + 1) % 2000 == 0) {
      const DaemonCounters c = core.counters();
      std::printf("   %-12d %10.1f %10lld %10lld %10lld\n", i + 1, RssMiB(), static_cast<long long>(c.plans),
                  static_cast<long long>(c.plans - c.dropped_requests - c.invalid_requests),
                  static_cast<long long>(c.dropped_requests));
    }
  }
  replies.WaitFor(static_cast<size_t>(latency_requests + memory_requests), std::chrono::seconds(600));
  const DaemonCounters c = core.counters();
  std::printf("   %-12s %10.1f %10lld %10lld %10lld\n", "all answered", RssMiB(), static_cast<long long>(c.plans),
              static_cast<long long>(c.plans - c.dropped_requests - c.invalid_requests),
              static_cast<long long>(c.dropped_requests));
  std::printf("   (* planned: replies with a plan since the start, both phases)\n");
  std::printf("   VmRSS at start %.1f MiB, before phase 2 %.1f MiB, after %.1f MiB\n", rss_start, rss_before,
              RssMiB());
  runner.Stop();
  return 0;
}

}  // namespace
}  // namespace mfp

int main(int argc, char** argv) {
  CLI::App app{"mfp-daemon-bench: request-to-plan latency and memory of the daemon"};
  std::string config = "config/daemon.yaml";
  int latency_requests = 100, memory_requests = 10000;
  double rate_hz = 10.0, time_limit_s = 2.0;
  app.add_option("--config", config, "daemon YAML")->capture_default_str();
  app.add_option("--requests", latency_requests, "requests in the latency phase")->capture_default_str();
  app.add_option("--rate", rate_hz, "request rate of the latency phase [Hz]")->capture_default_str();
  app.add_option("--memory-requests", memory_requests, "requests in the memory phase")->capture_default_str();
  app.add_option("--time-limit", time_limit_s, "per-request time limit [s]")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return mfp::Run(config, latency_requests, rate_hz, memory_requests, time_limit_s);
  } catch (const mfp::InputError& e) {
    std::fprintf(stderr, "mfp-daemon-bench: %s\n", e.what());
    return 2;
  }
}
