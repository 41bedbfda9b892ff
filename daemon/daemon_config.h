#pragma once
// Configuration of mfp-daemon (config/daemon.yaml), loaded and validated in one place.
#include <string>
#include <vector>

#include "io/option_table.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {

// LCM channels of the design; fixed by the contract.
inline constexpr const char* kTerrainMapChannel = "MFP_TERRAIN_MAP";
inline constexpr const char* kHeightMapChannel = "MFP_HEIGHT_MAP";  // height_map_t (extension)
inline constexpr const char* kPlanRequestChannel = "MFP_PLAN_REQUEST";
inline constexpr const char* kPlanChannel = "MFP_PLAN";
inline constexpr const char* kRegionsChannel = "MFP_REGIONS";
inline constexpr const char* kStatusChannel = "MFP_STATUS";

// What a request may ask for and what the daemon accepts on the wire.
struct DaemonLimits {
  double default_time_limit_s = 5.0;   // when plan_request_t.time_limit_s = 0 [s]
  double max_time_limit_s = 30.0;      // larger requested limits are rejected [s]
  int default_max_steps = 0;           // when plan_request_t.max_steps = 0; 0 = 12 n
  int max_steps = 120;                 // larger requests are rejected
  int queue_size = 4;                  // requests waiting; the oldest is dropped beyond
  size_t max_request_bytes = 64 * 1024;        // larger plan_request_t payloads are rejected
  size_t max_map_bytes = 64 * 1024 * 1024;     // larger terrain_map_t, height_map_t payloads are rejected
  // Messages received but not yet decoded (the intake queue between the LCM thread and
  // the decoding thread); beyond it a request is answered dropped and counted.
  int inbox_size = 4096;
  // A request's deadline is its arrival plus its time limit; the planner gets what is
  // left minus this margin, kept for the reply [s].
  double reply_margin_s = 0.03;
  // A newer request for the same robot replaces an older one still queued (answered
  // superseded): the robot is the client.
  bool supersede_same_robot = true;
  // A map without regions replaces a map with regions only when true.
  bool accept_empty_maps = false;
  // A robot's request is planned from the plans last sent to that robot on the same map,
  // this many of them (PlanRequest::warm_start; 0 = none): a robot replanning as it
  // walks gets its answer from the plan it is walking on (the robot may follow an older
  // reply than the newest sent).
  int warm_start_plans = 4;
  // Plans answered at their deadline but still stopping (their stop flag is set; they
  // end at their next check) may number this many at most: a request that finds that
  // many is answered dropped without a thread, so the daemon's threads stay bounded.
  int max_abandoned_plans = 2;
  // Threads one map's region extraction runs on (the map thread and this many minus one
  // helpers, joined before the map is published): on two cores extraction then takes
  // about half the wall time, while a plan in progress gets less of the machine.
  int extraction_threads = 2;
};

struct DaemonConfig {
  std::string file;                     // the YAML it came from ("" when built in code)
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";  // ttl=0: stays on this machine
  std::vector<std::string> robot_files;  // resolved paths (URDF or YAML)
  std::string default_robot;             // robot name used when a request names none
  std::string initial_map;               // resolved path of a map to start with; "" = none
  double heartbeat_period_s = 0.5;       // MFP_STATUS period, at most 1 s [s]
  // Messages LCM keeps per channel before it discards (LCM's default is 30): carries a
  // burst of requests while the intake thread catches up.
  int lcm_queue_capacity = 4096;
  // udpm:// socket receive buffer [bytes]; 0 = limits.max_map_bytes + 1 MiB, so the
  // largest accepted map fits (the kernel caps it at net.core.rmem_max; the daemon logs
  // when it does).
  size_t lcm_recv_buf_bytes = 0;
  DaemonLimits limits;
  PlannerOptions planner;
  std::vector<std::string> warnings;  // what the file should change (flat planner keys); the daemon logs them
};

// Loads and validates a daemon YAML; relative paths are resolved against its directory.
// Throws InputError naming the file, key and allowed range.
DaemonConfig LoadDaemonConfig(const std::string& path);

// The keys of a daemon YAML, for the reference (its planner: block: PlannerOptionDocs()).
std::vector<OptionDoc> DaemonOptionDocs();

}  // namespace mfp
