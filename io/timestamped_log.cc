#include "io/timestamped_log.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

namespace mfp {

int64_t WallUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void LogLine(const std::string& program, const std::string& text) {
  static std::mutex mutex;
  const int64_t utime = WallUtime();
  const std::time_t seconds = static_cast<std::time_t>(utime / 1000000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%dT%H:%M:%S", &tm);
  std::lock_guard<std::mutex> lock(mutex);
  std::fprintf(stderr, "%s.%03dZ %s: %s\n", stamp, static_cast<int>((utime / 1000) % 1000),
               program.c_str(), text.c_str());
  std::fflush(stderr);
}

}  // namespace mfp
