#pragma once
// The daemon's logic without threads or sockets: decodes untyped messages, validates
// requests, queues them (bounded, newest first), plans one on request, publishes
// replies, regions and status. mfp-daemon drives it from threads (daemon_runner.h);
// mfp-replay drives it from a log, one event at a time, deterministically; tests drive
// it directly. Thread-safe: OnMessage, PlanNext and PublishStatus may run concurrently.
// Never prints: log lines go to the LogSink.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lcmtypes/transport.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/plan_t.hpp"
#include "mfp/status_t.hpp"
#include "planner/planning/footstep_planner.h"
#include "planner/robot/robot_model.h"
#include "terrain/convex_region.h"
#include "tools/daemon/daemon_config.h"
#include "tools/daemon/request_queue.h"

namespace mfp {

// A config with its robots loaded, by name. Immutable once built; swapped whole on reload.
struct DaemonSetup {
  DaemonConfig config;
  std::map<std::string, RobotModel> robots;
};

// Plans one validated request. May throw (counted as internal_error); must honour
// request.time_limit_s.
using PlanFunction = std::function<Plan(const RobotModel& robot,
                                        const std::vector<ConvexRegion>& regions,
                                        const PlanRequest& request,
                                        const PlannerOptions& options)>;

// Turns the bytes of a map file into regions; throws InputError on a bad map. `what`
// names the source in messages.
using MapFunction = std::function<std::vector<ConvexRegion>(const std::string& bytes,
                                                            const std::string& format,
                                                            const std::string& what)>;

struct DaemonCounters {
  int64_t requests = 0;           // plan requests decoded
  int64_t plans = 0;              // plan_t replies published (every status)
  int64_t rejected_messages = 0;  // messages that could not be decoded
  int64_t invalid_requests = 0;   // requests answered with an input-error status
  int64_t dropped_requests = 0;   // requests answered with status dropped
  int64_t maps = 0;               // maps accepted
  int64_t rejected_maps = 0;      // maps decoded but unreadable
  int64_t internal_errors = 0;    // planner or handler failures
  double last_solve_time_s = -1;  // [s]
};

class DaemonCore {
 public:
  using Clock = std::function<int64_t()>;  // now [us]
  using LogSink = std::function<void(const std::string& line)>;

  DaemonCore(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function,
             PlanFunction plan_function, Publisher& publisher, Clock clock, LogSink log = {});

  // Subscribes OnMessage to MFP_TERRAIN_MAP and MFP_PLAN_REQUEST.
  void SubscribeTo(Transport& transport);

  // Handles one raw message from any channel. Never throws.
  void OnMessage(const RawMessage& message);

  // Reads a map file (the config's initial map). Throws InputError on a bad file.
  void LoadMapFile(const std::string& path);

  // Plans the newest queued request and publishes its reply. False when none was queued.
  bool PlanNext();
  // Waits up to `timeout` for a queued request, then plans it. False on timeout or stop.
  bool WaitAndPlanNext(std::chrono::milliseconds timeout);

  // Publishes status_t now.
  void PublishStatus();

  // Replaces the setup (config reload) and, when given, the map reader for the next
  // maps (the current regions stay). Queued requests stay; the queue takes the new
  // capacity (evicted entries are answered as dropped).
  void Reconfigure(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function = {});

  // Answers every queued request as dropped and wakes WaitAndPlanNext.
  void Stop();

  DaemonCounters counters() const;
  size_t queue_length() const;
  status_t StatusMessage() const;

 private:
  void HandleMap(const RawMessage& message);
  void HandleRequest(const RawMessage& message);
  void AcceptMap(const std::string& bytes, const std::string& format, const std::string& frame,
                 int64_t map_utime, const std::string& what);
  void Reply(const plan_t& reply);
  void ReplyDropped(const QueuedRequest& request, const std::string& why);
  void Log(const std::string& line) const;

  PlanFunction plan_function_;
  Publisher& publisher_;
  Clock clock_;
  LogSink log_;
  int64_t start_utime_;

  mutable std::mutex mutex_;
  std::condition_variable work_available_;
  bool stopped_ = false;
  bool planning_ = false;
  std::shared_ptr<const DaemonSetup> setup_;
  MapFunction map_function_;  // replaced on reload
  // Regions of the current map; shared so a plan in progress keeps its snapshot while a
  // new map replaces them.
  std::shared_ptr<const std::vector<ConvexRegion>> regions_;
  int64_t map_utime_ = 0;          // terrain_map_t.utime of the current map
  int64_t map_receive_utime_ = 0;  // clock when it arrived
  RequestQueue queue_;
  DaemonCounters counters_;
};

}  // namespace mfp
