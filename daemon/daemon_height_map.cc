// DaemonCore's height_map_t path: decoded and checked like a terrain_map_t, then read by
// the map function (format kHeightMapFormat) with the same queueing, replies and counters.
#include <mutex>

#include "base/check.h"
#include "daemon/daemon_core.h"
#include "daemon/height_map_message.h"
#include "lcmtypes/message_guard.h"

namespace mfp {

void DaemonCore::HandleHeightMap(const RawMessage& message, bool abandon_on_stop) {
  height_map_t map;
  if (!DecodeMap(message, &map)) return;
  const std::string what = "height_map_t utime " + std::to_string(map.utime);
  try {
    HeightGridFromMessage(map, what);  // the checks, before the extraction's work
    map.heights.clear();
    map.variances.clear();
    AcceptMap(std::string(message.data, message.data + message.size), kHeightMapFormat, map.frame,
              map.utime, what, abandon_on_stop);
  } catch (const InputError& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.rejected_maps;
    }
    Log(std::string("rejected map: ") + e.what());
  }
}

}  // namespace mfp
