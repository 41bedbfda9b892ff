#pragma once
// The daemon's logic without threads or sockets: decodes untyped messages, validates
// requests, queues them (bounded, newest first, a newer request for the same robot
// superseding an older one), plans one on request within its deadline (arrival plus
// time limit), publishes replies, regions and status. mfp-daemon drives it from threads
// (daemon_runner.h): the LCM thread only Receive()s (copies bytes into an intake queue),
// an intake thread decodes and validates, a map thread extracts regions, a worker plans.
// mfp-replay drives it from a log, one event at a time, with OnMessage and PlanNext;
// tests drive it directly. Thread-safe. Never prints: log lines go to the LogSink.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "daemon/abandonable_task.h"
#include "daemon/daemon_config.h"
#include "daemon/internal/request_queue.h"
#include "geometry/convex_region.h"
#include "geometry/seen_surface.h"
#include "lcmtypes/transport.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/plan_t.hpp"
#include "mfp/status_t.hpp"
#include "planner/planning/footstep_planner.h"
#include "planner/robot/robot_model.h"

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

// What a map gives the planner: the regions a foot may be put in, and the surface the map
// saw from above, where a start foot may already stand although no region holds it
// (PlanRequest::seen_surface; null: start feet on regions only).
struct MapTerrain {
  std::vector<ConvexRegion> regions;
  std::shared_ptr<const SeenSurface> seen_surface;
  // The body's obstacles in the map (PlanRequest::body_obstacles; null: none, as for a
  // height map or with the planner key map_body_obstacles off), and why there are none
  // when the extraction could not make them (empty otherwise).
  std::shared_ptr<const std::vector<BodyObstacle>> body_obstacles;
  std::string body_note;
};

// Turns the bytes of a map file into its terrain; throws InputError on a bad map. `what`
// names the source in messages.
using MapFunction = std::function<MapTerrain(const std::string& bytes, const std::string& format,
                                             const std::string& what)>;

// status_t documents each counter.
struct DaemonCounters {
  int64_t requests = 0;           // plan requests decoded
  int64_t plans = 0;              // plan_t replies published (every status)
  int64_t rejected_messages = 0;  // messages that could not be decoded
  int64_t invalid_requests = 0;   // requests answered with an input-error status
  int64_t dropped_requests = 0;   // requests answered with status dropped
  int64_t maps = 0;               // maps accepted
  int64_t rejected_maps = 0;      // maps decoded but unreadable
  int64_t internal_errors = 0;    // planner or handler failures
  int64_t superseded_requests = 0;
  int64_t expired_requests = 0;
  int64_t time_limit_endings = 0;
  int64_t abandoned_solves = 0;
  int64_t inbox_overflows = 0;
  int64_t superseded_maps = 0;
  int64_t empty_maps = 0;
  int64_t publish_failures = 0;
  double last_solve_time_s = -1;  // [s]
  // Not in status_t: plans abandoned at their deadline whose threads still run (a gauge).
  int64_t abandoned_plans_running = 0;
};

class DaemonCore {
 public:
  using Clock = std::function<int64_t()>;  // now [us]
  using LogSink = std::function<void(const std::string& line)>;

  DaemonCore(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function,
             PlanFunction plan_function, Publisher& publisher, Clock clock, LogSink log = {});

  // Subscribes Receive to MFP_TERRAIN_MAP, MFP_HEIGHT_MAP and MFP_PLAN_REQUEST.
  void SubscribeTo(Transport& transport);

  // The live receive path: copies the message into the intake queue (a request) or the
  // pending-map slot (a newer map replaces one not yet begun), and returns. Payloads over
  // the size caps are counted and discarded here; a request that finds the intake queue
  // full is decoded here only to be answered dropped. Never throws.
  void Receive(const RawMessage& message);
  // Intake thread: waits up to `timeout` for a received request, decodes, validates and
  // queues it. False on timeout or stop.
  bool ProcessNextReceived(std::chrono::milliseconds timeout);
  // Map thread: waits up to `timeout` for a received map and reads it. False on timeout
  // or stop. A stop abandons an extraction in progress.
  bool ProcessPendingMap(std::chrono::milliseconds timeout);

  // Handles one raw message from any channel on the calling thread (mfp-replay, tests).
  // Never throws.
  void OnMessage(const RawMessage& message);

  // Reads a map file (the config's initial map). Throws InputError on a bad file.
  void LoadMapFile(const std::string& path);

  // Plans the newest queued request and publishes its reply. False when none was queued.
  // The reply goes out by the request's deadline: when the planner has not returned by
  // then (or on Stop), the request is answered time_limit (dropped on Stop) and the
  // planner's thread is left to finish unobserved.
  bool PlanNext();
  // Waits up to `timeout` for a queued request, then plans it. False on timeout or stop.
  bool WaitAndPlanNext(std::chrono::milliseconds timeout);

  // Publishes status_t now.
  void PublishStatus();

  // Replaces the setup (config reload) and, when given, the map reader for the next
  // maps (the current regions stay). Queued requests stay; the queue takes the new
  // capacity (evicted entries are answered as dropped).
  void Reconfigure(std::shared_ptr<const DaemonSetup> setup, MapFunction map_function = {});

  // Answers every queued and received request as dropped, makes a plan or map
  // extraction in progress give up waiting (its request answered dropped), wakes the
  // waiting threads.
  void Stop();

  // How plan and map tasks get their threads (default: a detached std::thread each).
  // For tests (a launcher that fails) and embedders; set before the first request.
  void SetTaskLauncher(TaskLauncher launcher);

  // Kernel UDP receive errors to show in status_t (-1: unknown). Optional.
  void SetUdpErrorSource(std::function<int64_t()> source);

  DaemonCounters counters() const;
  size_t queue_length() const;
  status_t StatusMessage() const;

 private:
  struct Received {
    std::string channel;
    std::vector<uint8_t> bytes;
    int64_t arrival_utime = 0;  // clock_ when received [us]
    // A view of the bytes; valid while this Received lives.
    RawMessage AsRaw() const {
      RawMessage raw;
      raw.channel = channel;
      raw.data = bytes.data();
      raw.size = bytes.size();
      return raw;
    }
  };
  // A request taken from the queue to plan, with the setup and map it is planned on.
  struct PlanJob {
    QueuedRequest queued;
    std::shared_ptr<const DaemonSetup> setup;
    std::shared_ptr<const std::vector<ConvexRegion>> regions;
    std::shared_ptr<const SeenSurface> seen_surface;  // of the same map as regions
    std::shared_ptr<const std::vector<BodyObstacle>> body_obstacles;  // of the same map; null: none
    int64_t map_utime = 0;
    std::string map_frame;
    std::vector<std::vector<Footstep>> warm_start;
    double limit_s = 0.0;   // the request's time limit, from its arrival [s]
    double waited_s = 0.0;  // spent in the queue [s]
  };

  // Planning (daemon_planning.cc).
  std::optional<PlanJob> TakeNextJob();
  Plan RunPlanner(PlanJob& job, const RobotModel& robot, bool* abandoned);
  // The reply to a job that must not be planned (deadline passed in the queue, robot
  // gone, too many abandoned plans still stopping); nullopt when it may be planned.
  std::optional<Plan> RefuseJob(const PlanJob& job);
  Plan AnswerAtDeadline(const PlanJob& job, Plan so_far);
  void RecordOutcome(const PlanJob& job, const Plan& plan, bool abandoned);
  void PublishFootholds(const PlanJob& job, const Plan& plan);

  void HandleMap(const RawMessage& message, bool abandon_on_stop);
  // Decodes a map message (terrain_map_t, height_map_t) within limits.max_map_bytes;
  // false, counted rejected, when it does not decode (daemon_maps.cc).
  template <class MapMessage>
  bool DecodeMap(const RawMessage& message, MapMessage* map);
  // A height_map_t (daemon_height_map.cc): checked, then read like a map file.
  void HandleHeightMap(const RawMessage& message, bool abandon_on_stop);
  void HandleRequest(const RawMessage& message, int64_t arrival_utime);
  // Decodes a request that will not be planned and answers it dropped (or counts it
  // rejected when it does not decode).
  void AnswerUnplanned(const Received& received, const std::string& why);
  void AcceptMap(const std::string& bytes, const std::string& format, const std::string& frame,
                 int64_t map_utime, const std::string& what, bool abandon_on_stop);
  void Reply(plan_t reply);
  void ReplyStatus(const QueuedRequest& request, SolveStatus status, const std::string& why);
  void CountRejected(const std::string& channel, const std::string& error);
  void CountInternalError(const std::string& doing, const std::exception& e);
  void CountPublishFailure(const std::string& channel);
  template <class Message>
  void Publish(const std::string& channel, const Message& message) {
    if (!PublishMessage(publisher_, channel, message)) CountPublishFailure(channel);
  }
  void Log(const std::string& line) const;

  PlanFunction plan_function_;
  Publisher& publisher_;
  Clock clock_;
  LogSink log_;
  int64_t start_utime_;

  mutable std::mutex mutex_;
  std::condition_variable work_available_;
  std::condition_variable received_available_;
  std::condition_variable map_available_;
  std::atomic<bool> stopped_{false};
  TaskLauncher launcher_ = LaunchDetachedThread;
  // Plan tasks whose planner has not returned: the one being waited for, if any, and the
  // abandoned ones still stopping.
  std::shared_ptr<std::atomic<int>> plan_tasks_ = std::make_shared<std::atomic<int>>(0);
  bool planning_ = false;
  bool extracting_ = false;
  std::deque<Received> received_;        // requests received, not yet decoded
  std::optional<Received> pending_map_;  // newest map received, not yet begun
  std::function<int64_t()> udp_errors_;
  std::shared_ptr<const DaemonSetup> setup_;
  MapFunction map_function_;  // replaced on reload
  // Regions of the current map; shared so a plan in progress keeps its snapshot while a
  // new map replaces them.
  std::shared_ptr<const std::vector<ConvexRegion>> regions_;
  std::shared_ptr<const SeenSurface> seen_surface_;  // of the current map; null: none
  std::shared_ptr<const std::vector<BodyObstacle>> body_obstacles_;  // of the current map; null: none
  int64_t map_utime_ = 0;          // terrain_map_t.utime of the current map
  std::string map_frame_;          // its frame, for region sets published with a plan
  int64_t map_receive_utime_ = 0;  // clock when it arrived
  RequestQueue queue_;
  DaemonCounters counters_;
  // Footsteps of the plans last sent to each robot on the current map, newest first
  // (cleared when the map or the config changes): the warm start of its next request
  // (limits.warm_start_plans of them).
  std::map<std::string, std::vector<std::vector<Footstep>>> last_plans_;
};

}  // namespace mfp
