#include "lcmtypes/event_log_writer.h"

#include <vector>

#include "base/check.h"

namespace mfp {

EventLogWriter::EventLogWriter(const std::string& path) {
  log_ = lcm_eventlog_create(path.c_str(), "w");
  if (log_ == nullptr) throw InputError("cannot create the LCM log '" + path + "'");
}

EventLogWriter::~EventLogWriter() { lcm_eventlog_destroy(log_); }

bool EventLogWriter::Write(const std::string& channel, const void* data, size_t size,
                           int64_t utime) {
  if (size > static_cast<size_t>(INT32_MAX)) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<char> channel_copy(channel.begin(), channel.end());
  channel_copy.push_back('\0');
  lcm_eventlog_event_t event{};
  event.timestamp = utime;
  event.channellen = static_cast<int32_t>(channel.size());
  event.channel = channel_copy.data();
  event.datalen = static_cast<int32_t>(size);
  event.data = const_cast<void*>(data);  // lcm_eventlog_write_event only reads it
  return lcm_eventlog_write_event(log_, &event) == 0;
}

bool EventLogWriter::Publish(const std::string& channel, const void* data, size_t size) {
  int64_t utime = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    utime = utime_;
  }
  return Write(channel, data, size, utime);
}

void EventLogWriter::SetTime(int64_t utime) {
  std::lock_guard<std::mutex> lock(mutex_);
  utime_ = utime;
}

}  // namespace mfp
