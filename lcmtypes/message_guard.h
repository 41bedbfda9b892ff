#pragma once
// Guarded decoding of untyped LCM payloads. LCM 1.3.1's generated decoders resize
// arrays to the length read from the wire before checking it against the buffer, so a
// negative or huge length throws or allocates gigabytes. DecodeGuarded caps the size,
// checks the fingerprint, walks the wire layout of the inbound types to check every
// array and string length against the bytes that remain, catches decoder exceptions,
// and requires the decoder to consume exactly the message.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "mfp/height_map_t.hpp"
#include "mfp/plan_request_t.hpp"
#include "mfp/terrain_map_t.hpp"

namespace mfp {

// Checks the lengths in a payload against its size by walking the type's wire layout.
// Returns "" when the layout fits exactly, else the problem. Only the inbound types
// have a walker; tests check that each walk matches the generated encoder.
std::string CheckWireLayout(const plan_request_t* tag, const uint8_t* data, size_t size);
std::string CheckWireLayout(const terrain_map_t* tag, const uint8_t* data, size_t size);
std::string CheckWireLayout(const height_map_t* tag, const uint8_t* data, size_t size);
// Types without a walker (the daemon's own outputs, read back by tools and tests).
template <class Message>
std::string CheckWireLayout(const Message* /*tag*/, const uint8_t* /*data*/, size_t /*size*/) {
  return "";
}

// Largest number of legs a plan_request_t may carry (a cap on allocation, not a robot
// limit; requests are checked against the robot afterwards).
constexpr int kMaxWireLegs = 64;

// Largest height_map_t side (cells along x or y); the message size cap bounds nx * ny.
constexpr int kMaxWireHeightMapSide = 65536;

// Decodes data[0, size) into *out. Returns "" on success, else a reason that names the
// problem ("3 bytes, shorter than the 8-byte fingerprint", "fingerprint ... expected ...").
template <class Message>
std::string DecodeGuarded(const uint8_t* data, size_t size, size_t max_size, Message* out) {
  if (size > max_size)
    return std::to_string(size) + " bytes, above the limit of " + std::to_string(max_size);
  if (size < 8) return std::to_string(size) + " bytes, shorter than the 8-byte fingerprint";
  uint64_t hash = 0;
  for (int i = 0; i < 8; ++i) hash = (hash << 8) | data[i];
  const uint64_t expected = static_cast<uint64_t>(Message::getHash());
  if (hash != expected) return "fingerprint does not match " + std::string(Message::getTypeName());
  const std::string layout = CheckWireLayout(static_cast<const Message*>(nullptr), data, size);
  if (!layout.empty()) return layout;
  int consumed = -1;
  try {
    consumed = out->decode(data, 0, static_cast<int>(size));
  } catch (const std::exception& e) {
    return std::string("decoder failed: ") + e.what();
  }
  if (consumed < 0) return "malformed " + std::string(Message::getTypeName());
  if (static_cast<size_t>(consumed) != size)
    return std::to_string(size) + " bytes but " + Message::getTypeName() + " uses " +
           std::to_string(consumed);
  return "";
}

}  // namespace mfp
