#include "lcmtypes/message_guard.h"

namespace mfp {
namespace {

// Reads LCM's big-endian wire format, remembering the first problem.
class WireCursor {
 public:
  WireCursor(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  size_t remaining() const { return size_ - pos_; }
  const std::string& error() const { return error_; }
  bool ok() const { return error_.empty(); }

  void Skip(size_t bytes, const char* what) {
    if (!ok()) return;
    if (bytes > remaining()) {
      Fail(std::string(what) + " needs " + std::to_string(bytes) + " bytes, " +
           std::to_string(remaining()) + " remain");
      return;
    }
    pos_ += bytes;
  }

  int32_t ReadInt32(const char* what) {
    if (!ok()) return 0;
    if (remaining() < 4) {
      Fail(std::string(what) + ": truncated");
      return 0;
    }
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | data_[pos_ + i];
    pos_ += 4;
    return static_cast<int32_t>(v);
  }

  // Reads a length field and checks it against [min, max] and the bytes that remain
  // for elements of element_size bytes each.
  int32_t ReadLength(const char* what, int32_t min, int32_t max, size_t element_size) {
    const int32_t n = ReadInt32(what);
    if (!ok()) return 0;
    if (n < min || n > max) {
      Fail(std::string(what) + " = " + std::to_string(n) + ", allowed [" +
           std::to_string(min) + ", " + std::to_string(max) + "]");
      return 0;
    }
    if (static_cast<size_t>(n) * element_size > remaining()) {
      Fail(std::string(what) + " = " + std::to_string(n) + " does not fit in the " +
           std::to_string(remaining()) + " bytes that remain");
      return 0;
    }
    return n;
  }

  // What every mfp message starts with: LCM's 8-byte type fingerprint, then int64 utime.
  void SkipFingerprintAndUtime() {
    Skip(8, "fingerprint");
    Skip(8, "utime");
  }

  // An LCM string: int32 length including the terminating NUL, then the bytes.
  void SkipString(const char* what) {
    const int32_t n = ReadLength(what, 1, INT32_MAX, 1);
    if (!ok()) return;
    if (data_[pos_ + static_cast<size_t>(n) - 1] != 0) {
      Fail(std::string(what) + ": string not terminated");
      return;
    }
    pos_ += static_cast<size_t>(n);
  }

  // The walk must end exactly at the end of the message.
  std::string Finish(const char* type) {
    if (ok() && remaining() != 0)
      Fail(std::to_string(remaining()) + " bytes after the end of " + type);
    return error_;
  }

 private:
  void Fail(const std::string& why) {
    if (error_.empty()) error_ = why;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  std::string error_;
};

}  // namespace

std::string CheckWireLayout(const plan_request_t* /*tag*/, const uint8_t* data, size_t size) {
  WireCursor cursor(data, size);
  cursor.SkipFingerprintAndUtime();
  cursor.Skip(8, "request_id");
  cursor.SkipString("robot");
  const int32_t legs = cursor.ReadLength("num_legs", 0, kMaxWireLegs, 3 * 8);
  cursor.Skip(static_cast<size_t>(legs) * 3 * 8, "start_feet");
  cursor.Skip(3 * 8, "goal_x, goal_y, goal_yaw");
  cursor.Skip(4, "max_steps");
  cursor.Skip(8, "time_limit_s");
  return cursor.Finish("plan_request_t");
}

std::string CheckWireLayout(const terrain_map_t* /*tag*/, const uint8_t* data, size_t size) {
  WireCursor cursor(data, size);
  cursor.SkipFingerprintAndUtime();
  cursor.SkipString("frame");
  cursor.SkipString("format");
  const int32_t bytes = cursor.ReadLength("num_bytes", 0, INT32_MAX, 1);
  cursor.Skip(static_cast<size_t>(bytes), "data");
  return cursor.Finish("terrain_map_t");
}

std::string CheckWireLayout(const height_map_t* /*tag*/, const uint8_t* data, size_t size) {
  WireCursor cursor(data, size);
  cursor.SkipFingerprintAndUtime();
  cursor.SkipString("frame");
  cursor.Skip(3 * 8, "resolution, origin_x, origin_y");
  const int32_t nx = cursor.ReadLength("nx", 0, kMaxWireHeightMapSide, 0);
  const int32_t ny = cursor.ReadLength("ny", 0, kMaxWireHeightMapSide, 0);
  const size_t cells = static_cast<size_t>(nx) * static_cast<size_t>(ny);
  cursor.Skip(cells * 4, "heights");
  const int32_t variances = cursor.ReadLength("num_variances", 0, INT32_MAX, 4);
  cursor.Skip(static_cast<size_t>(variances) * 4, "variances");
  cursor.Skip(8, "max_variance");
  return cursor.Finish("height_map_t");
}

}  // namespace mfp
