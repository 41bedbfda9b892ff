#pragma once
// Log lines of the executables (never of libraries): "2024-05-01T12:00:00.123Z mfp-daemon: text"
// on stderr, one line at a time from any thread.
#include <string>

namespace mfp {

void LogLine(const std::string& program, const std::string& text);

// Microseconds since the Unix epoch (the utime of LCM messages).
int64_t WallUtime();

}  // namespace mfp
