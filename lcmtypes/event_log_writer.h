#pragma once
// Writes an LCM log file (the format lcm-logger writes and lcm-logplayer reads).
// As a Publisher it stamps each event with the time set by SetTime, so replays write
// deterministic logs.
#include <lcm/eventlog.h>

#include <mutex>
#include <string>

#include "lcmtypes/transport.h"

namespace mfp {

class EventLogWriter final : public Publisher {
 public:
  // Throws InputError when the file cannot be created.
  explicit EventLogWriter(const std::string& path);
  ~EventLogWriter() override;
  EventLogWriter(const EventLogWriter&) = delete;
  EventLogWriter& operator=(const EventLogWriter&) = delete;

  // Writes one event at utime [us]. Returns false when writing fails.
  bool Write(const std::string& channel, const void* data, size_t size, int64_t utime);
  // Publisher: writes at the time last given to SetTime.
  bool Publish(const std::string& channel, const void* data, size_t size) override;
  void SetTime(int64_t utime);

 private:
  std::mutex mutex_;
  lcm_eventlog_t* log_ = nullptr;
  int64_t utime_ = 0;
};

}  // namespace mfp
