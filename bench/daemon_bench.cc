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
//  3. Replanning soak (--soak-minutes N): a robot replanning as it walks, at --soak-rate
//     (10 Hz) for N minutes, on the stepping stones and on a real-size seeded field of
//     stones (--soak-map). The robot walks one gait cycle of the plan it follows every
//     --soak-cycle s (0.5), its feet landing within 3 mm of the planned spots (seeded),
//     and follows a reply planned from the stance it still stands in; each request starts
//     from its current stance, 12 new footsteps towards the goal, time limit
//     --soak-time-limit. It patrols: at the goal (or stuck) it turns back for its start
//     spot; lost (invalid start, infeasible, no route) it starts again. Per minute:
//     replies, p50/p90/p99/max reply latency (publish to receipt, every reply), drops,
//     supersessions, time-limit endings, requests unanswered or answered more than once,
//     VmRSS and threads; then the planner's own solve times, nodes and proven gaps; then
//     the reply latency distribution and the slowest 1 % one per line with what its plan
//     did (set-up and route, windows, nodes, its first window warm or cold, the wait
//     behind the plan before it) and what the robot did before asking.
//     --soak-cold plans every request from scratch; --soak-field-side 25
//     --soak-field-pitch 0.21 makes the field 500+ regions (577). The goal is moved to the
//     nearest pose whose nominal foot spots all lie near a region (GoalOnRegions): one
//     with a spot between stones is answered no_route at every request.
//  4. Burst (--burst N, 2000): N requests published at once; every one answered once, or
//     counted.
// Prints a table; timing is never a pass/fail criterion.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <malloc.h>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <thread>
#include <utility>

#include "base/check.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_core.h"
#include "daemon/daemon_runner.h"
#include "daemon/daemon_setup.h"
#include "daemon/heap_release.h"
#include "daemon/map_regions.h"
#include "daemon/solver_plan_function.h"
#include "geometry/convex_region.h"
#include "io/cli_parse.h"
#include "io/scenario_yaml.h"
#include "io/terrain_yaml.h"
#include "lcmtypes/lcm_transport.h"
#include "lcmtypes/message_guard.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/plan_t.hpp"
#include "mfp/terrain_map_t.hpp"
#include "planner/planning/footstep_planner.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/voxelize.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/terrain_catalogue.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

// A number of /proc/self/status ("VmRSS:", "Threads:"); -1 when absent.
double ProcStatus(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == field) {
      double value = 0;
      in >> value;
      return value;
    }
    std::getline(in, key);
  }
  return -1;
}

double RssMiB() { return ProcStatus("VmRSS:") / 1024.0; }

// The allocator's account (glibc mallinfo2, every arena): bytes in use (heap chunks and
// mmapped blocks) and bytes free but kept by the allocator [MiB].
struct HeapMiB {
  double in_use = 0, kept_free = 0;
};
HeapMiB HeapNow() {
  const struct mallinfo2 m = mallinfo2();
  return {static_cast<double>(m.uordblks + m.hblkhd) / (1 << 20), static_cast<double>(m.fordblks) / (1 << 20)};
}
int ThreadCount() { return static_cast<int>(ProcStatus("Threads:")); }

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

terrain_map_t MapMessage(const TerrainDescription& terrain) {
  terrain_map_t map{};
  map.utime = NowUs();
  map.frame = "world";
  map.format = "bt";
  map.data = OccupancyMapBytes(VoxelizeTerrain(terrain), true);
  map.num_bytes = static_cast<int32_t>(map.data.size());
  return map;
}

// Publishes the map and waits until the daemon has accepted it.
void PublishMapAndWait(Publisher& transport, const DaemonCore& core, const terrain_map_t& map) {
  const auto map_bytes = Encode(map);
  transport.Publish(kTerrainMapChannel, map_bytes.data(), map_bytes.size());
  while (core.counters().maps == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
}

// The robot's nominal stance at the origin; max_steps new footsteps towards a goal 0.25 m
// ahead.
plan_request_t NominalRequest(const RobotModel& robot, int max_steps, double time_limit_s) {
  plan_request_t request{};
  request.num_legs = robot.num_legs();
  for (const LegModel& leg : robot.legs)
    request.start_feet.push_back({leg.nominal_offset_body_m.x(), leg.nominal_offset_body_m.y(), 0.0});
  request.goal_x = 0.25;
  request.max_steps = max_steps;
  request.time_limit_s = time_limit_s;
  return request;
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

int RunClassic(const std::shared_ptr<const DaemonSetup>& setup, int latency_requests, double rate_hz,
               int memory_requests, double time_limit_s) {
  const RobotModel& hexapod = setup->robots.at("hexapod");

  // Flat ground, 4 m x 3 m, as an OctoMap through the daemon's own map pipeline.
  TerrainDescription terrain;
  TerrainBox ground;
  ground.name = "ground";
  ground.center_world_m = Eigen::Vector3d(1.0, 0.0, -0.05);
  ground.size_m = Eigen::Vector3d(4.0, 3.0, 0.1);
  terrain.boxes.push_back(ground);
  const terrain_map_t map = MapMessage(terrain);

  LcmTransport transport("memq://", setup->config.lcm_queue_capacity);
  DaemonCore core(setup, MakeOctomapMapFunction(*setup), MakeSolverPlanFunction(), transport, &NowUs);
  core.SubscribeTo(transport);
  ReplyLog replies;
  transport.Subscribe(kPlanChannel, [&](const RawMessage& raw) {
    plan_t p;
    if (DecodeGuarded(raw.data, raw.size, 1 << 24, &p).empty()) replies.Add(p);
  });
  const double rss_start = RssMiB();
  DaemonRunner runner(core, transport, setup->config.heartbeat_period_s);
  PublishMapAndWait(transport, core, map);

  plan_request_t request = NominalRequest(hexapod, 12, time_limit_s);

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

// A real-size field, seeded: a 1.2 m start pad at the origin and 200 stones of 0.21 m on
// a 0.27 m grid (the stepping stones' spacing) over 4.1 m x 4.1 m, tops within +-3 cm:
// every stone one of the extractor's regions (it keeps 256 at most). The goal, 1.485 m
// ahead, puts every foot of the nominal stance on a stone.
// side x side stones `pitch_m` apart (each 0.78 pitch wide) about a start pad.
TerrainDescription StoneField(uint32_t seed, int side, double pitch_m) {
  TerrainDescription terrain;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> height(-0.03, 0.03);
  TerrainBox pad;
  pad.name = "pad";
  pad.center_world_m = Eigen::Vector3d(0, 0, -0.05);
  pad.size_m = Eigen::Vector3d(1.2, 1.2, 0.1);
  terrain.boxes.push_back(pad);
  const int half = side / 2;
  for (int i = -half; i <= half; ++i) {
    for (int j = -half; j <= half; ++j) {
      const double x = pitch_m * i, y = pitch_m * j;
      // Not on the pad: a stone overlapping its edge (the ring at 0.54 m) cuts the pad's
      // region where the hind feet of the start stance stand.
      if (std::abs(x) < 0.75 && std::abs(y) < 0.75) continue;
      TerrainBox stone;
      stone.name = "stone";
      stone.center_world_m = Eigen::Vector3d(x, y, height(rng) - 0.05);
      stone.size_m = Eigen::Vector3d(0.78 * pitch_m, 0.78 * pitch_m, 0.1);
      terrain.boxes.push_back(stone);
    }
  }
  return terrain;
}

// Whether every foot spot of the nominal stance at (x, y, yaw) lies within within_m of a
// region in plan view (the route's test of a goal, with goal_tolerance).
bool StanceNearRegions(const RobotModel& robot, const std::vector<ConvexRegion>& regions, double x, double y,
                       double yaw, double within_m) {
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d foot = NominalFootXY(robot, leg, x, y, yaw);
    if (std::none_of(regions.begin(), regions.end(),
                     [&](const ConvexRegion& r) { return PlanDistanceToRegion(r, foot) <= within_m; }))
      return false;
  }
  return true;
}

// A goal pose near the wanted one whose nominal stance has every foot spot within half
// the goal tolerance of a region: a goal with a foot spot farther from every region is
// answered no_route at every request. x moves by up to 0.5 m, y by up to 0.1 m (5 mm
// steps) and the yaw by up to 0.2 rad (0.05 rad steps), the nearest first in that order;
// the wanted pose when none fits.
Eigen::Vector3d GoalOnRegions(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                              const Eigen::Vector3d& wanted, double goal_tolerance_m) {
  for (int i = 0; i <= 100; ++i) {
    for (const double x : {wanted.x() + 0.005 * i, wanted.x() - 0.005 * i}) {
      for (int j = 0; j <= 20; ++j) {
        for (const double y : {wanted.y() + 0.005 * j, wanted.y() - 0.005 * j}) {
          for (int k = 0; k <= 4; ++k) {
            for (const double yaw : {wanted.z() + 0.05 * k, wanted.z() - 0.05 * k}) {
              if (StanceNearRegions(robot, regions, x, y, yaw, 0.5 * goal_tolerance_m)) return Eigen::Vector3d(x, y, yaw);
            }
          }
        }
      }
    }
  }
  return wanted;
}

// What the planner did for one plan, found again by its solve time: plan_t carries
// Plan::solve_time_s unchanged (microsecond resolution, unique to a plan in practice). A
// reply answered at the deadline carries its own time and has no trace.
struct PlanTrace {
  SolveStatus status = SolveStatus::kInternalError;
  double setup_s = 0;
  int windows = 0, nodes = 0;
  std::vector<WindowRecord> records;
};

class PlanTraces {
 public:
  void Add(const Plan& p) {
    std::lock_guard<std::mutex> lock(mutex_);
    traces_[p.solve_time_s] = {p.status, p.setup_s, p.windows, p.nodes, p.window_records};
  }
  const PlanTrace* Find(double solve_time_s) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto found = traces_.find(solve_time_s);
    return found == traces_.end() ? nullptr : &found->second;
  }

 private:
  mutable std::mutex mutex_;
  std::map<double, PlanTrace> traces_;
};

// The daemon's own plan function, each plan's trace kept.
PlanFunction TracedPlanFunction(const std::shared_ptr<PlanTraces>& traces) {
  return [inner = MakeSolverPlanFunction(), traces](const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                                     const PlanRequest& request, const PlannerOptions& options) {
    Plan plan = inner(robot, regions, request, options);
    traces->Add(plan);
    return plan;
  };
}

// How the first window of a traced plan started: from scratch, or from the client's
// previous plan (matched: seeds only; bounded: replan_time_s search; fell back: the
// bounded search found nothing and the full search ran).
std::string WarmKind(const PlanTrace& t) {
  if (t.records.empty()) return "no window";
  const WindowRecord& r = t.records.front();
  if (r.replan_fell_back) return "fell back";
  if (r.bounded_replan) return "bounded";
  return r.warm_matched ? "matched" : "cold";
}

struct SoakReply {
  int64_t id;
  double latency_ms;
  int8_t status;
  double solve_time_s;
  std::string event;  // what the robot did just before sending the request
};

// The latency distribution of every reply, then the slowest 1 % one per line with what
// its plan did (the wait is the rest of the latency: queued behind the plan before it),
// and the slowest 1 % and all replies counted by event and by first-window start.
void PrintLatencyTail(std::vector<SoakReply> replies, const PlanTraces& traces) {
  if (replies.empty()) return;
  std::sort(replies.begin(), replies.end(),
            [](const SoakReply& a, const SoakReply& b) { return a.latency_ms > b.latency_ms; });
  std::vector<double> latency;
  for (const SoakReply& r : replies) latency.push_back(r.latency_ms);
  std::printf("   reply latency distribution [ms]:");
  for (const double p : {0.5, 0.75, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999, 1.0})
    std::printf(" p%g %.1f", 100 * p, Percentile(latency, p));
  std::printf("\n   replies by latency:");
  const double edges[] = {25, 50, 75, 100, 150, 200, 300, 500};
  for (size_t b = 0; b <= std::size(edges); ++b) {
    const double lo = b == 0 ? 0 : edges[b - 1], hi = b == std::size(edges) ? 1e300 : edges[b];
    const auto count = std::count_if(latency.begin(), latency.end(), [&](double v) { return v >= lo && v < hi; });
    if (b == std::size(edges)) std::printf(" >=%.0f: %ld", lo, static_cast<long>(count));
    else std::printf(" %.0f-%.0f: %ld", lo, hi, static_cast<long>(count));
  }
  const size_t tail = std::max<size_t>(1, replies.size() / 100);
  std::printf("\n   the slowest 1 %% (%zu replies): id, latency, status, solve, wait = latency - solve, set-up "
              "(checks, route), windows, nodes, first window (start, search s, its share s, heuristic s, polish s, "
              "nodes), event before the request\n", tail);
  std::map<std::string, std::pair<int, int>> by_event, by_start;  // (in the tail, all)
  for (size_t i = 0; i < replies.size(); ++i) {
    const SoakReply& r = replies[i];
    const PlanTrace* t = HasPlan(static_cast<SolveStatus>(r.status)) || r.status == plan_t::STATUS_TIME_LIMIT
                             ? traces.Find(r.solve_time_s) : nullptr;
    const std::string start = t ? WarmKind(*t) : (r.status == plan_t::STATUS_SUPERSEDED ? "superseded" : "no trace");
    (i < tail ? by_event[r.event].first : by_event[r.event].second)++;
    (i < tail ? by_start[start].first : by_start[start].second)++;
    if (i >= tail) continue;
    std::printf("   %6lld %7.1f ms %-10s solve %6.1f wait %6.1f", static_cast<long long>(r.id), r.latency_ms,
                ToString(static_cast<SolveStatus>(r.status)).c_str(), 1e3 * r.solve_time_s,
                r.latency_ms - 1e3 * r.solve_time_s);
    if (t != nullptr) {
      std::printf(" setup %5.1f windows %d nodes %4d", 1e3 * t->setup_s, t->windows, t->nodes);
      if (!t->records.empty()) {
        const WindowRecord& w = t->records.front();
        std::printf(" | %-9s %.3f of %.3f, rf %.3f, polish %.3f, %d nodes", start.c_str(), w.search_s,
                    w.time_limit_s, w.heuristic_s, w.polish_s, w.nodes);
      }
    } else {
      std::printf(" (%s)", start.c_str());
    }
    std::printf(" | %s\n", r.event.c_str());
  }
  std::printf("   tail / all by event before the request:");
  for (const auto& [name, n] : by_event) std::printf(" %s %d/%d", name.c_str(), n.first, n.first + n.second);
  std::printf("\n   tail / all by the first window's start:");
  for (const auto& [name, n] : by_start) std::printf(" %s %d/%d", name.c_str(), n.first, n.first + n.second);
  std::printf("\n");
}

struct SoakCourse {
  std::string name;
  TerrainDescription terrain;
  double goal_x = 0, goal_y = 0, goal_yaw = 0;
};

// What one soak runs on and at what pace: the daemon's set-up, the course, its map and
// regions, the goal moved onto the regions, and Soak's pace arguments.
struct SoakRun {
  std::shared_ptr<const DaemonSetup> setup;
  const SoakCourse& course;
  const RobotModel& robot;
  terrain_map_t map;
  std::vector<ConvexRegion> regions;
  Eigen::Vector3d goal_pose;  // the course's goal moved onto the regions (x, y, yaw)
  double minutes, rate_hz, time_limit_s, cycle_s;
};

// A reply to a soak request, as the robot received it.
struct SoakAnswer {
  int64_t latency_us;
  int8_t status;
  double solve_time_s;
  int nodes;
  double gap;
};

// The robot: it walks the gait cycles of the plan it follows, one every cycle_s, and
// asks for a new plan from the stance it stands in at the request rate. A reply is
// followed when its request was sent from the stance the robot still stands in (a plan
// from an older stance starts where the robot no longer is). It patrols: at the goal it
// turns back for its start spot (keeping the goal's heading), and so on. Shared by the
// sender (the soak's loop) and the plan handler (the transport's thread): the members
// after `mutex` only under it.
struct SoakRobot {
  SoakRobot(const SoakRun& run, std::vector<Eigen::Vector3d> start_feet)
      : n(run.robot.num_legs()),
        start(std::move(start_feet)),
        course_goal_x(run.goal_pose.x()),
        course_goal_y(run.goal_pose.y()),
        goal_yaw(run.goal_pose.z()),
        feet(start),
        goal_x(course_goal_x),
        goal_y(course_goal_y) {}

  const int n;                                // legs
  const std::vector<Eigen::Vector3d> start;   // the stance it starts (and restarts) from
  const double course_goal_x, course_goal_y;  // the far end of its patrol
  const double goal_yaw;
  std::mutex mutex;
  std::vector<Eigen::Vector3d> feet;          // where the robot stands now
  int stance_version = 0;                     // +1 at each gait cycle walked or reset
  std::map<int64_t, int64_t> sent_us;         // by request id
  std::map<int64_t, int> sent_stance;         // stance_version of each request
  std::map<int64_t, std::string> sent_event;  // what the robot did just before each request
  std::string last_event = "first";           // since the last request sent
  std::vector<footstep_t> followed;           // steps of the plan the robot follows
  int next_cycle = 1;                         // its next gait cycle to walk (0 is the start)
  std::map<int64_t, std::vector<SoakAnswer>> answers;
  int resets = 0, cycles_walked = 0, arrivals = 0, turns = 0;
  bool stuck_here = false;    // turned back stuck, not walked since
  std::string first_refusal;  // the first reply without a plan (other than superseded)
  double furthest_m = 0;      // from the start, of the centre of the feet
  double goal_x, goal_y;      // the end it is walking to
  // Feet land near, not on, the planned spots: a seeded error of up to 3 mm per axis.
  std::mt19937 landing_rng{19};
  std::uniform_real_distribution<double> landing_error{-0.003, 0.003};

  void TurnBack() {
    const bool outward = goal_x == course_goal_x && goal_y == course_goal_y;
    goal_x = outward ? 0.0 : course_goal_x;
    goal_y = outward ? 0.0 : course_goal_y;
    followed.clear();
    last_event = "turned back";
  }

  // A reply received at now_us: recorded, and acted on when planned from the stance the
  // robot stands in. Under the mutex.
  void OnPlan(const plan_t& p, int64_t now_us) {
    const auto sent = sent_us.find(p.request_id);
    if (sent == sent_us.end()) return;
    answers[p.request_id].push_back({now_us - sent->second, p.status, p.solve_time_s, p.nodes, p.gap});
    const auto status = static_cast<SolveStatus>(p.status);
    if (!HasPlan(status) && status != SolveStatus::kSuperseded && first_refusal.empty())
      first_refusal = "request " + std::to_string(p.request_id) + ": " + ToString(status) + ": " + p.message;
    if (sent_stance[p.request_id] != stance_version) return;  // planned from where the robot was
    if (HasPlan(status) && p.num_steps >= 2 * n) {
      followed = p.steps;
      next_cycle = 1;
    } else if (HasPlan(status) && p.reaches_goal) {
      TurnBack();  // standing at the goal
      ++arrivals;
    } else if (HasPlan(status) && !stuck_here) {
      TurnBack();  // stuck short of the goal without a step to take
      stuck_here = true;
      ++turns;
    } else if (HasPlan(status) || status == SolveStatus::kInvalidStart || status == SolveStatus::kInfeasible ||
               status == SolveStatus::kNoRoute) {
      // Lost, or stuck both ways: start again.
      stuck_here = false;
      feet = start;  // lost: start again
      goal_x = course_goal_x;
      goal_y = course_goal_y;
      followed.clear();
      ++stance_version;
      ++resets;
      last_event = "restarted";
    }
  }

  // Walks the next gait cycle of the followed plan, if it has one. Under the mutex.
  void WalkCycle() {
    if (static_cast<int>(followed.size()) < (next_cycle + 1) * n) return;
    for (int k = next_cycle * n; k < (next_cycle + 1) * n; ++k) {
      const footstep_t& step = followed[static_cast<size_t>(k)];
      if (step.leg >= 0 && step.leg < n)
        feet[static_cast<size_t>(step.leg)] =
            Eigen::Vector3d(step.position[0] + landing_error(landing_rng),
                            step.position[1] + landing_error(landing_rng), step.position[2]);
    }
    ++next_cycle;
    ++stance_version;
    stuck_here = false;
    ++cycles_walked;
    last_event = "walked";
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& f : feet) centre += f / n;
    furthest_m = std::max(furthest_m, std::hypot(centre.x(), centre.y()));
    if (std::hypot(centre.x() - goal_x, centre.y() - goal_y) < 0.1) {
      TurnBack();  // arrived: back to the other end, from where the robot stands
      ++arrivals;
    }
  }

  // Request `id` from where the robot stands to where it is going, recorded as sent now
  // (its stance and the event before it). Under the mutex.
  void Ask(int64_t id, plan_request_t* request) {
    for (const auto& f : feet) request->start_feet.push_back({f.x(), f.y(), f.z()});
    sent_us[id] = NowUs();
    sent_stance[id] = stance_version;
    sent_event[id] = last_event;
    last_event = "same stance";
    request->goal_x = goal_x;
    request->goal_y = goal_y;
    request->goal_yaw = goal_yaw;
  }
};

// Every reply of the soak so far, for the whole soak's lines.
struct SoakTally {
  std::vector<double> all_latency_ms, all_solve_ms, all_nodes, all_gaps;
  int most_threads = ThreadCount();  // sampled at every request and minute row
  std::map<std::string, int> all_statuses;
  std::vector<SoakReply> all_replies;
};

void PrintSoakHeading(const SoakRun& run) {
  const SoakCourse& course = run.course;
  std::printf("\n3. replanning soak on %s (%zu regions, %zu map bytes): %s, %.0f Hz for %.1f min, "
              "%d new footsteps per request, time limit %.2f s, a gait cycle walked every %.2f s; goal (%.3f, %.3f, "
              "%.3f)%s\n",
              course.name.c_str(), run.regions.size(), run.map.data.size(), run.robot.name.c_str(), run.rate_hz,
              run.minutes, 2 * run.robot.num_legs(), run.time_limit_s, run.cycle_s, run.goal_pose.x(),
              run.goal_pose.y(), run.goal_pose.z(),
              run.goal_pose != Eigen::Vector3d(course.goal_x, course.goal_y, course.goal_yaw)
                  ? " (moved: the goal asked for has a foot spot off every region)"
                  : "");
  std::printf("   %-6s %7s %7s %8s %8s %8s %8s %8s %9s %9s %9s %9s %9s %8s %9s %9s\n", "minute", "sent", "plans",
              "p50 ms", "p90 ms", "p99 ms", "max ms", "dropped", "supersed.", "time lim.",
              "unanswer.", "answ.>1", "VmRSS MiB", "threads", "heap used", "heap free");
}

// The row of the requests first..last (one minute's) and their replies; adds the replies
// to the tally.
void ReportMinute(SoakRobot& robot, SoakTally* tally, int64_t first, int64_t last, const std::string& label) {
  std::vector<double> latency_ms;
  std::map<int, int> by_status;
  int unanswered = 0, planned = 0, answered_twice = 0;
  std::lock_guard<std::mutex> lock(robot.mutex);
  for (int64_t id = first; id <= last; ++id) {
    const auto found = robot.answers.find(id);
    if (found == robot.answers.end()) {
      ++unanswered;
      continue;
    }
    if (found->second.size() > 1) ++answered_twice;
    for (const SoakAnswer& a : found->second) {
      latency_ms.push_back(1e-3 * static_cast<double>(a.latency_us));
      tally->all_latency_ms.push_back(latency_ms.back());
      tally->all_replies.push_back({id, latency_ms.back(), a.status, a.solve_time_s, robot.sent_event[id]});
      ++by_status[a.status];
      ++tally->all_statuses[ToString(static_cast<SolveStatus>(a.status))];
      if (HasPlan(static_cast<SolveStatus>(a.status))) {
        ++planned;
        tally->all_solve_ms.push_back(1e3 * a.solve_time_s);
        tally->all_nodes.push_back(a.nodes);
        tally->all_gaps.push_back(100.0 * a.gap);
      }
    }
  }
  const HeapMiB heap = HeapNow();
  std::printf("   %-6s %7lld %7d %8.1f %8.1f %8.1f %8.1f %8d %9d %9d %9d %9d %9.1f %8d %9.1f %9.1f\n", label.c_str(),
              static_cast<long long>(last - first + 1), planned, Percentile(latency_ms, 0.5),
              Percentile(latency_ms, 0.9), Percentile(latency_ms, 0.99), Percentile(latency_ms, 1.0),
              by_status[plan_t::STATUS_DROPPED], by_status[plan_t::STATUS_SUPERSEDED],
              by_status[plan_t::STATUS_TIME_LIMIT], unanswered, answered_twice, RssMiB(), ThreadCount(),
              heap.in_use, heap.kept_free);
  tally->most_threads = std::max(tally->most_threads, ThreadCount());
  std::fflush(stdout);
}

// The robot's requests at the soak's rate, walking a gait cycle every cycle_s, with a row
// per minute (the sender pauses at each minute's end for its last replies).
void SendSoakRequests(const SoakRun& run, SoakRobot& robot, SoakTally* tally, LcmTransport& transport) {
  const int n = robot.n;
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / run.rate_hz));
  const int total = static_cast<int>(std::lround(run.minutes * 60.0 * run.rate_hz));
  const int requests_per_cycle = std::max(1, static_cast<int>(std::lround(run.cycle_s * run.rate_hz)));
  const int per_minute = static_cast<int>(std::lround(60.0 * run.rate_hz));
  auto next = Clock::now();
  int64_t first_of_minute = 1;
  for (int i = 1; i <= total; ++i) {
    std::this_thread::sleep_until(next);
    next += period;
    plan_request_t request{};
    request.request_id = i;
    request.utime = NowUs();
    request.num_legs = n;
    {
      std::lock_guard<std::mutex> lock(robot.mutex);
      if (i > 1 && (i - 1) % requests_per_cycle == 0) robot.WalkCycle();
      robot.Ask(i, &request);
    }
    request.max_steps = 2 * n;
    request.time_limit_s = run.time_limit_s;
    const auto bytes = Encode(request);
    transport.Publish(kPlanRequestChannel, bytes.data(), bytes.size());
    tally->most_threads = std::max(tally->most_threads, ThreadCount());
    if (i % per_minute == 0 || i == total) {
      // The minute's last requests get their time limit (and a little) to be answered.
      std::this_thread::sleep_for(std::chrono::duration<double>(run.time_limit_s + 0.2));
      next = Clock::now();
      ReportMinute(robot, tally, first_of_minute, i, std::to_string((i + per_minute - 1) / per_minute));
      first_of_minute = i + 1;
    }
  }
}

// The whole soak's lines: reply latency and statuses, the planner's solve times, nodes and
// gaps, the daemon's counters and the robot's walk, then the latency tail.
void PrintSoakSummary(const SoakRun& run, const SoakTally& t, const SoakRobot& robot, const DaemonCounters& c,
                      const PlanTraces& traces) {
  std::printf("   whole soak: reply latency p50 %.1f ms, p90 %.1f ms, p99 %.1f ms, max %.1f ms; replies by status:",
              Percentile(t.all_latency_ms, 0.5), Percentile(t.all_latency_ms, 0.9),
              Percentile(t.all_latency_ms, 0.99), Percentile(t.all_latency_ms, 1.0));
  for (const auto& [name, count] : t.all_statuses) std::printf(" %s %d", name.c_str(), count);
  std::printf("\n   planner solve time of the plans: p50 %.1f ms, p90 %.1f ms, p99 %.1f ms, max %.1f ms; "
              "branch-and-bound nodes p50 %.0f, p99 %.0f (the rest of a reply's latency is the wait for the "
              "plan before it)",
              Percentile(t.all_solve_ms, 0.5), Percentile(t.all_solve_ms, 0.9), Percentile(t.all_solve_ms, 0.99),
              Percentile(t.all_solve_ms, 1.0), Percentile(t.all_nodes, 0.5), Percentile(t.all_nodes, 0.99));
  std::printf("\n   proven gap of the plans (objective over the search's bound; 0 = proven optimal): p50 %.2f %%, "
              "p90 %.2f %%, p99 %.2f %%",
              Percentile(t.all_gaps, 0.5), Percentile(t.all_gaps, 0.9), Percentile(t.all_gaps, 0.99));
  std::printf("\n   daemon counters: requests %lld, replies %lld, superseded %lld, dropped %lld, expired %lld, "
              "time-limit endings %lld, abandoned solves %lld, intake overflows %lld, publish failures %lld, "
              "most threads %d (limits.max_abandoned_plans %d); "
              "gait cycles walked %d, furthest %.2f m from the start, goals reached %d, turned back stuck %d, course restarts %d\n",
              static_cast<long long>(c.requests), static_cast<long long>(c.plans),
              static_cast<long long>(c.superseded_requests), static_cast<long long>(c.dropped_requests),
              static_cast<long long>(c.expired_requests), static_cast<long long>(c.time_limit_endings),
              static_cast<long long>(c.abandoned_solves), static_cast<long long>(c.inbox_overflows),
              static_cast<long long>(c.publish_failures), t.most_threads, run.setup->config.limits.max_abandoned_plans,
              robot.cycles_walked, robot.furthest_m, robot.arrivals, robot.turns, robot.resets);
  if (!robot.first_refusal.empty()) std::printf("   first reply without a plan: %s\n", robot.first_refusal.c_str());
  PrintLatencyTail(t.all_replies, traces);
  std::printf("   (minute rows: the requests sent in that minute and their replies; the sender pauses %.1f s "
              "at each minute's end so they are all in)\n", run.time_limit_s + 0.2);
  std::fflush(stdout);
}

// One soak: a fresh daemon, a walking robot, a table per minute.
void Soak(const std::shared_ptr<const DaemonSetup>& setup, const SoakCourse& course, double minutes,
          double rate_hz, double time_limit_s, double cycle_s) {
  const RobotModel& robot = setup->robots.at(setup->config.default_robot);
  SoakRun run{setup, course, robot, MapMessage(course.terrain), {}, {}, minutes, rate_hz, time_limit_s, cycle_s};
  run.regions = MakeOctomapMapFunction(*setup)(std::string(run.map.data.begin(), run.map.data.end()), "bt",
                                               course.name).regions;
  std::vector<Eigen::Vector3d> start = NominalStance(robot, run.regions, 0, 0, 0);
  run.goal_pose = GoalOnRegions(robot, run.regions, Eigen::Vector3d(course.goal_x, course.goal_y, course.goal_yaw),
                                setup->config.planner.goal_tolerance_m);

  LcmTransport transport("memq://", setup->config.lcm_queue_capacity);
  const auto traces = std::make_shared<PlanTraces>();
  DaemonCore core(setup, MakeOctomapMapFunction(*setup), TracedPlanFunction(traces), transport, &NowUs);
  core.SubscribeTo(transport);

  SoakRobot walker(run, std::move(start));
  transport.Subscribe(kPlanChannel, [&](const RawMessage& raw) {
    plan_t p;
    if (!DecodeGuarded(raw.data, raw.size, 1 << 24, &p).empty()) return;
    const int64_t now = NowUs();
    std::lock_guard<std::mutex> lock(walker.mutex);
    walker.OnPlan(p, now);
  });
  DaemonRunner runner(core, transport, setup->config.heartbeat_period_s);
  PublishMapAndWait(transport, core, run.map);

  PrintSoakHeading(run);
  SoakTally tally;
  SendSoakRequests(run, walker, &tally, transport);
  runner.Stop();
  while (transport.HandleTimeout(50) > 0) {
  }
  PrintSoakSummary(run, tally, walker, core.counters(), *traces);
}

// N requests published back to back: each answered exactly once, or counted.
void Burst(const std::shared_ptr<const DaemonSetup>& setup, int count, double time_limit_s) {
  const RobotModel& robot = setup->robots.at(setup->config.default_robot);
  const SoakCourse flat{"flat", FlatTerrain()};
  const terrain_map_t map = MapMessage(flat.terrain);
  LcmTransport transport("memq://", setup->config.lcm_queue_capacity);
  DaemonCore core(setup, MakeOctomapMapFunction(*setup), MakeSolverPlanFunction(), transport, &NowUs);
  core.SubscribeTo(transport);
  std::mutex mutex;
  std::map<int64_t, int> replies;
  std::map<std::string, int> statuses;
  transport.Subscribe(kPlanChannel, [&](const RawMessage& raw) {
    plan_t p;
    if (!DecodeGuarded(raw.data, raw.size, 1 << 24, &p).empty()) return;
    std::lock_guard<std::mutex> lock(mutex);
    ++replies[p.request_id];
    ++statuses[ToString(static_cast<SolveStatus>(p.status))];
  });
  DaemonRunner runner(core, transport, setup->config.heartbeat_period_s);
  PublishMapAndWait(transport, core, map);
  plan_request_t request = NominalRequest(robot, 12, time_limit_s);
  const auto start = Clock::now();
  for (int i = 1; i <= count; ++i) {
    request.request_id = i;
    request.utime = NowUs();
    const auto bytes = Encode(request);
    transport.Publish(kPlanRequestChannel, bytes.data(), bytes.size());
  }
  const double publish_s = std::chrono::duration<double>(Clock::now() - start).count();
  for (int i = 0; i < 600; ++i) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (replies.size() >= static_cast<size_t>(count)) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const double answer_s = std::chrono::duration<double>(Clock::now() - start).count();
  runner.Stop();
  while (transport.HandleTimeout(50) > 0) {
  }
  const DaemonCounters c = core.counters();
  std::lock_guard<std::mutex> lock(mutex);
  int twice = 0;
  for (const auto& entry : replies) twice += entry.second > 1 ? 1 : 0;
  std::printf("\n4. burst: %d requests published at once (%.3f s to publish), LCM queue %d, intake %d\n",
              count, publish_s, setup->config.lcm_queue_capacity, setup->config.limits.inbox_size);
  std::printf("   answered %zu of %d (%d more than once) in %.2f s; by status:", replies.size(), count,
              twice, answer_s);
  for (const auto& [name, n] : statuses) std::printf(" %s %d", name.c_str(), n);
  std::printf("\n   daemon counters: requests %lld, replies %lld, rejected messages %lld, superseded %lld, "
              "dropped %lld, intake overflows %lld, publish failures %lld\n",
              static_cast<long long>(c.requests), static_cast<long long>(c.plans),
              static_cast<long long>(c.rejected_messages), static_cast<long long>(c.superseded_requests),
              static_cast<long long>(c.dropped_requests), static_cast<long long>(c.inbox_overflows),
              static_cast<long long>(c.publish_failures));
}

}  // namespace
}  // namespace mfp

int main(int argc, char** argv) {
  CLI::App app{"mfp-daemon-bench: request-to-plan latency and memory of the daemon"};
  std::string config = "config/daemon.yaml";
  int latency_requests = 100, memory_requests = 10000;
  double rate_hz = 10.0, time_limit_s = 2.0;
  double soak_minutes = 0, soak_rate_hz = 10.0, soak_time_limit_s = 0.5, soak_cycle_s = 0.5;
  std::string soak_map = "both";
  int field_side = 15;
  double field_pitch_m = 0.27;
  double field_goal_x_m = 1.485;
  std::string stones = "config/scenarios/hexapod_stepping_stones_90.yaml";
  int burst = 0;
  app.add_option("--config", config, "daemon YAML")->capture_default_str();
  app.add_option("--requests", latency_requests, "requests in the latency phase")->capture_default_str();
  app.add_option("--rate", rate_hz, "request rate of the latency phase [Hz]")->capture_default_str();
  app.add_option("--memory-requests", memory_requests, "requests in the memory phase")->capture_default_str();
  app.add_option("--time-limit", time_limit_s, "per-request time limit [s]")->capture_default_str();
  app.add_flag("--skip-classic", "skip phases 1 and 2");
  app.add_option("--soak-minutes", soak_minutes, "replanning soak length per map [min]; 0 = none")
      ->capture_default_str();
  app.add_option("--soak-rate", soak_rate_hz, "replanning rate [Hz]")->capture_default_str();
  app.add_option("--soak-time-limit", soak_time_limit_s, "replanning time limit [s]")->capture_default_str();
  app.add_option("--soak-cycle", soak_cycle_s, "the robot walks one gait cycle of its plan every this long [s]")
      ->capture_default_str();
  app.add_option("--soak-map", soak_map, "stones, field or both")
      ->check(CLI::IsMember({"stones", "field", "both"}))
      ->capture_default_str();
  app.add_option("--soak-field-side", field_side, "stones per side of the soak's field")->capture_default_str();
  app.add_option("--soak-field-pitch", field_pitch_m, "between the field's stone centres [m]")
      ->capture_default_str();
  app.add_option("--soak-field-goal-x", field_goal_x_m, "the field's goal, x [m] (y and yaw 0)")->capture_default_str();
  app.add_option("--stones", stones, "the stepping stones scenario of the soak")->capture_default_str();
  app.add_option("--burst", burst, "requests published at once; 0 = none")->capture_default_str();
  app.add_flag("--soak-cold", "plan every soak request from scratch (limits.warm_start_plans: 0)");
  MFP_CLI_PARSE(app, argc, argv);
  mfp::BoundHeapRetention();  // as mfp-daemon does at start
  try {
    mfp::DaemonConfig daemon_config = mfp::LoadDaemonConfig(config);
    if (app.count("--soak-cold") > 0) daemon_config.limits.warm_start_plans = 0;
    auto setup = std::make_shared<const mfp::DaemonSetup>(mfp::LoadDaemonSetup(daemon_config));
    if (app.count("--skip-classic") == 0)
      mfp::RunClassic(setup, latency_requests, rate_hz, memory_requests, time_limit_s);
    if (soak_minutes > 0) {
      std::printf("(VmRSS is the whole bench process: daemon and client)\n");
      if (soak_map != "field") {
        const mfp::Scenario scenario = mfp::LoadScenario(stones);
        mfp::SoakCourse course{"stepping stones (" + stones + ")", mfp::LoadTerrainDescription(stones),
                               scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad};
        mfp::Soak(setup, course, soak_minutes, soak_rate_hz, soak_time_limit_s, soak_cycle_s);
      }
      if (soak_map != "stones") {
        const double extent_m = field_pitch_m * (field_side / 2 * 2 + 1);
        char name[160];
        std::snprintf(name, sizeof name, "a %.1f m x %.1f m field of %d x %d stones less the pad (seed 19)", extent_m,
                      extent_m, field_side / 2 * 2 + 1, field_side / 2 * 2 + 1);
        mfp::SoakCourse course{name, mfp::StoneField(19, field_side, field_pitch_m), field_goal_x_m, 0.0, 0.0};
        mfp::Soak(setup, course, soak_minutes, soak_rate_hz, soak_time_limit_s, soak_cycle_s);
      }
    }
    if (burst > 0) mfp::Burst(setup, burst, soak_time_limit_s);
    return 0;
  } catch (const mfp::InputError& e) {
    std::fprintf(stderr, "mfp-daemon-bench: %s\n", e.what());
    return 2;
  }
}
