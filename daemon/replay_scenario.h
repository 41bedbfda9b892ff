#pragma once
// Scenario files for LCM logs (mfp-make-log writes the log, mfp-check-replies checks the
// daemon's replies against the expectations):
//
//   terrain: {resolution: 0.02, boxes: [...]}   # the map (terrain_yaml.h); or map: FILE.bt
//   map_at_s: 0.5                               # when the map is sent [s from the log start]
//   as_height_map: true      # optional: send the terrain's boxes as a height_map_t on
//                            # MFP_HEIGHT_MAP (sampled at its resolution), not an OctoMap
//   requests:
//     - at_s: 1.0            # when the request is sent [s]
//       id: 1                # request_id
//       robot: hexapod       # optional; "" = the daemon's default robot
//       start: [x, y, yaw]   # nominal stance at this pose on the map's regions
//       start_feet: [[x, y, z], ...]   # or the feet themselves (leg order)
//       legs: 4              # optional: send only this many feet (a wrong leg count)
//       goal: [x, y, yaw]    # numbers may be .nan or .inf to test rejections
//       max_steps: 12        # optional (0 = default)
//       time_limit_s: 10     # optional (0 = default)
//       expect: plan         # "plan" (a status with footsteps, valid on the regions),
//                            # "reaches_goal" (the same, reaching the goal) or a status name
//       expect_message: "num_legs"     # optional: a part of the reply's message
//   malformed:               # payloads the daemon must count and survive
//     - {at_s: 0.8, channel: MFP_PLAN_REQUEST, kind: truncated}
//       channels: MFP_PLAN_REQUEST, MFP_TERRAIN_MAP, MFP_HEIGHT_MAP
//       kinds: truncated, random, wrong_fingerprint, negative_length, oversized, empty
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/terrain_description.h"

namespace mfp {

struct ScenarioRequest {
  double at_s = 0.0;
  int64_t id = 0;
  std::string robot;
  std::optional<Eigen::Vector3d> start_pose;                // x, y, yaw
  std::vector<Eigen::Vector3d> start_feet_world_m;          // when given explicitly
  std::optional<int> legs;                                  // send only this many feet
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();           // x, y, yaw (may be non-finite)
  int max_steps = 0;
  double time_limit_s = 0.0;
  std::string expect = "plan";
  std::string expect_message;
};

struct ScenarioMalformed {
  double at_s = 0.0;
  std::string channel;
  std::string kind;
};

struct ReplayScenario {
  std::string file;
  std::optional<TerrainDescription> terrain;  // either terrain or map_file
  std::string map_file;
  double map_at_s = 0.0;
  bool as_height_map = false;  // the terrain goes out as a height_map_t
  std::vector<ScenarioRequest> requests;
  std::vector<ScenarioMalformed> malformed;
};

// Throws InputError naming the file, key and allowed range.
ReplayScenario LoadReplayScenario(const std::string& path);

// A malformed payload of the given kind for a channel (MFP_PLAN_REQUEST, MFP_TERRAIN_MAP
// or MFP_HEIGHT_MAP), derived from a valid message of the channel's type; seeded, so logs
// are reproducible. oversize_bytes is the size of "oversized" payloads. Throws
// InputError on an unknown kind or channel.
std::vector<uint8_t> MalformedPayload(const std::string& kind, const std::string& channel,
                                      size_t oversize_bytes, uint32_t seed);

// The kinds MalformedPayload knows.
const std::vector<std::string>& MalformedKinds();

}  // namespace mfp
