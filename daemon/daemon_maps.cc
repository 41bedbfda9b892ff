// DaemonCore's map handling: decode a map message or read a map file, extract its
// regions (abandonable on stop), swap them in and publish them.
#include "daemon/daemon_core.h"

#include "base/bounded_file.h"
#include "base/check.h"
#include "daemon/abandonable_task.h"
#include "daemon/message_conversion.h"
#include "lcmtypes/message_guard.h"
#include "mfp/height_map_t.hpp"
#include "mfp/terrain_map_t.hpp"

namespace mfp {

template <class MapMessage>
bool DaemonCore::DecodeMap(const RawMessage& message, MapMessage* map) {
  size_t max_bytes = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    max_bytes = setup_->config.limits.max_map_bytes;
  }
  const std::string error = DecodeGuarded(message.data, message.size, max_bytes, map);
  if (error.empty()) return true;
  CountRejected(message.channel, error);
  return false;
}
template bool DaemonCore::DecodeMap(const RawMessage&, terrain_map_t*);
template bool DaemonCore::DecodeMap(const RawMessage&, height_map_t*);

void DaemonCore::HandleMap(const RawMessage& message, bool abandon_on_stop) {
  if (message.channel == kHeightMapChannel) return HandleHeightMap(message, abandon_on_stop);
  terrain_map_t map;
  if (!DecodeMap(message, &map)) return;
  const std::string bytes(map.data.begin(), map.data.end());
  map.data.clear();
  try {
    AcceptMap(bytes, map.format, map.frame, map.utime,
              "terrain_map_t utime " + std::to_string(map.utime), abandon_on_stop);
  } catch (const InputError& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.rejected_maps;
    }
    Log(std::string("rejected map: ") + e.what());
  }
  // Anything else (no thread for the extraction: std::system_error) is counted by the
  // caller as an internal error; the current map stays.
}

void DaemonCore::LoadMapFile(const std::string& path) {
  const std::string bytes = ReadBoundedRegularFile(path, setup_->config.limits.max_map_bytes, "initial_map");
  const size_t dot = path.rfind('.');
  const std::string format = dot == std::string::npos ? "" : path.substr(dot + 1);
  AcceptMap(bytes, format, "world", clock_(), path, /*abandon_on_stop=*/false);
}

void DaemonCore::AcceptMap(const std::string& bytes, const std::string& format,
                           const std::string& frame, int64_t map_utime, const std::string& what,
                           bool abandon_on_stop) {
  MapFunction map_function;
  TaskLauncher launcher;
  bool accept_empty = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    map_function = map_function_;
    launcher = launcher_;
    accept_empty = setup_->config.limits.accept_empty_maps;
    extracting_ = true;
  }
  // Extraction runs outside the lock: requests keep being answered meanwhile.
  std::optional<MapTerrain> extracted;
  try {
    if (abandon_on_stop) {
      // On a thread of its own that a stop stops waiting for (the extractor has no stop
      // flag of its own yet).
      AbandonableTask<MapTerrain> task(
          [map_function, bytes, format, what] { return map_function(bytes, format, what); }, nullptr,
          launcher);
      extracted = task.Wait(std::chrono::steady_clock::time_point::max(), stopped_);
    } else {
      extracted = map_function(bytes, format, what);
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    extracting_ = false;
    throw;
  }
  const int64_t now = clock_();
  std::shared_ptr<const std::vector<ConvexRegion>> regions;
  size_t kept_regions = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    extracting_ = false;
    if (!extracted) {
      // Only a stop ends the wait without a result.
    } else if (extracted->regions.empty() && !accept_empty && regions_ != nullptr && !regions_->empty()) {
      ++counters_.empty_maps;
      kept_regions = regions_->size();
    } else {
      regions = std::make_shared<const std::vector<ConvexRegion>>(std::move(extracted->regions));
      regions_ = regions;
      seen_surface_ = std::move(extracted->seen_surface);
      body_obstacles_ = std::move(extracted->body_obstacles);
      map_utime_ = map_utime;
      map_frame_ = frame;
      last_plans_.clear();
      map_receive_utime_ = now;
      ++counters_.maps;
    }
  }
  if (!extracted) {
    Log("map extraction abandoned (" + what + "): the daemon is stopping");
    return;
  }
  if (regions == nullptr) {
    Log("map refused (" + what + "): it has no regions; the current map (" +
        std::to_string(kept_regions) +
        " regions) stays (set limits.accept_empty_maps to take such maps)");
    return;
  }
  Publish(kRegionsChannel, ToRegionSetMessage(*regions, frame, now, map_utime));
  Log("map accepted (" + what + "): " + std::to_string(bytes.size()) + " bytes, " +
      std::to_string(regions->size()) + " regions" +
      (extracted->body_obstacles ? ", " + std::to_string(extracted->body_obstacles->size()) + " body obstacles" : ""));
  if (!extracted->body_note.empty()) Log("map (" + what + "): " + extracted->body_note);
}

}  // namespace mfp
