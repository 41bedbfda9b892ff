#include "lcmtypes/event_log_reader.h"

#include <filesystem>

#include "base/check.h"

namespace mfp {
namespace {

constexpr uint64_t kHeaderBytes = 4 + 8 + 8 + 4 + 4;

uint64_t BigEndian(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

void PutBigEndian(uint64_t v, int bytes, std::vector<uint8_t>* out) {
  for (int i = bytes - 1; i >= 0; --i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

}  // namespace

EventLogReader::EventLogReader(const std::string& path, uint64_t max_event_bytes)
    : path_(path), max_event_bytes_(max_event_bytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError("cannot open the LCM log '" + path + "': not a regular file");
  }
  file_size_ = std::filesystem::file_size(path, ec);
  if (ec) throw InputError("cannot open the LCM log '" + path + "': " + ec.message());
  in_.open(path, std::ios::binary);
  if (!in_) throw InputError("cannot open the LCM log '" + path + "'");
}

void EventLogReader::Fail(const std::string& what) const {
  throw InputError("LCM log '" + path_ + "': event " + std::to_string(index_) + " at byte " +
                   std::to_string(offset_) + ": " + what);
}

bool EventLogReader::Next(LogEvent* event) {
  if (offset_ == file_size_) return false;
  const uint64_t left = file_size_ - offset_;
  if (left < kHeaderBytes) {
    Fail("truncated header (" + std::to_string(left) + " bytes left, a header has " +
         std::to_string(kHeaderBytes) + "): the log was cut short");
  }
  uint8_t header[kHeaderBytes];
  if (!in_.read(reinterpret_cast<char*>(header), kHeaderBytes)) Fail("read error");
  const auto sync = static_cast<uint32_t>(BigEndian(header, 4));
  if (sync != kLogSyncWord) Fail("no sync word (not an LCM log, or corrupt)");
  const auto channel_len = static_cast<int32_t>(BigEndian(header + 20, 4));
  const auto data_len = static_cast<int32_t>(BigEndian(header + 24, 4));
  if (channel_len <= 0 || channel_len > kMaxLogChannelBytes) {
    Fail("channel name length " + std::to_string(channel_len) + " is outside [1, " +
         std::to_string(kMaxLogChannelBytes) + "]");
  }
  if (data_len < 0) Fail("negative data length " + std::to_string(data_len));
  const uint64_t body = static_cast<uint64_t>(channel_len) + static_cast<uint64_t>(data_len);
  if (body > left - kHeaderBytes) {
    Fail("claims " + std::to_string(channel_len) + " channel and " + std::to_string(data_len) +
         " data bytes but only " + std::to_string(left - kHeaderBytes) +
         " remain in the file: the log is truncated or corrupt");
  }
  if (static_cast<uint64_t>(data_len) > max_event_bytes_) {
    Fail("data of " + std::to_string(data_len) + " bytes exceeds the limit of " +
         std::to_string(max_event_bytes_));
  }
  event->event_number = static_cast<int64_t>(BigEndian(header + 4, 8));
  event->utime = static_cast<int64_t>(BigEndian(header + 12, 8));
  event->channel.resize(static_cast<size_t>(channel_len));
  event->data.resize(static_cast<size_t>(data_len));
  if (!in_.read(event->channel.data(), channel_len) ||
      !in_.read(reinterpret_cast<char*>(event->data.data()), data_len)) {
    Fail("read error");
  }
  offset_ += kHeaderBytes + body;
  ++index_;
  return true;
}

std::vector<uint8_t> EncodeLogFrame(int64_t event_number, int64_t utime, const std::string& channel,
                                    const std::vector<uint8_t>& data) {
  std::vector<uint8_t> out;
  PutBigEndian(kLogSyncWord, 4, &out);
  PutBigEndian(static_cast<uint64_t>(event_number), 8, &out);
  PutBigEndian(static_cast<uint64_t>(utime), 8, &out);
  PutBigEndian(channel.size(), 4, &out);
  PutBigEndian(data.size(), 4, &out);
  out.insert(out.end(), channel.begin(), channel.end());
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

}  // namespace mfp
