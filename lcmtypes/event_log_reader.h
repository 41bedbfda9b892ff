#pragma once
// Reads an LCM log file event by event with its own bounded reader, not liblcm's
// (lcm_eventlog_read_next_event trusts the lengths an event claims: an event claiming
// 2^31 - 1 bytes crashed mfp-replay inside liblcm). Every frame is checked before its
// bytes are read: the sync word, a channel name of 1..kMaxLogChannelBytes bytes, a data
// length that fits in what is left of the file and under the caller's cap. A log that
// breaks any of these is an InputError naming the event's index, its byte offset and
// what is wrong; the events before it have been returned. The format (LCM's, all
// integers big-endian): u32 sync 0xEDA1DA01, i64 event number, i64 timestamp [us],
// i32 channel length, i32 data length, channel bytes, data bytes.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace mfp {

constexpr uint32_t kLogSyncWord = 0xEDA1DA01u;
constexpr int32_t kMaxLogChannelBytes = 256;  // LCM channel names are at most 63 bytes

struct LogEvent {
  int64_t event_number = 0;
  int64_t utime = 0;  // [us]
  std::string channel;
  std::vector<uint8_t> data;
};

class EventLogReader {
 public:
  // Opens the log; throws InputError when it cannot be read. Events whose data exceed
  // max_event_bytes are refused as an error (a log of this program's messages has none).
  EventLogReader(const std::string& path, uint64_t max_event_bytes);
  // Reads the next event into *event. Returns false at the clean end of the log; throws
  // InputError on a frame that is truncated, unsynchronised or claims impossible sizes.
  bool Next(LogEvent* event);

 private:
  [[noreturn]] void Fail(const std::string& what) const;

  std::string path_;
  std::ifstream in_;
  uint64_t file_size_ = 0;
  uint64_t offset_ = 0;  // of the next frame
  uint64_t index_ = 0;   // of the next frame, from 0
  uint64_t max_event_bytes_;
};

// Encodes one frame in the same format (for tests and generators of hostile logs).
std::vector<uint8_t> EncodeLogFrame(int64_t event_number, int64_t utime, const std::string& channel,
                                    const std::vector<uint8_t>& data);

}  // namespace mfp
