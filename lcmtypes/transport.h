#pragma once
// A message transport the daemon publishes to and receives from, untyped: channel plus
// bytes. LcmTransport (lcm_transport.h) talks to a real LCM URL (udpm://, memq://,
// file://); tests may implement this interface with a fake. Handlers receive raw bytes
// and decode them with the guards of message_guard.h, never with LCM's typed
// subscription (which aborts the process on some malformed payloads).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace mfp {

// One received message. data is valid only during the handler call.
struct RawMessage {
  std::string channel;
  const uint8_t* data = nullptr;
  size_t size = 0;
  int64_t receive_utime = 0;  // transport's receive time (log time for file://) [us]
};

using RawHandler = std::function<void(const RawMessage& message)>;

// The sending half: where the daemon's replies go (a transport, or a log file).
class Publisher {
 public:
  virtual ~Publisher() = default;
  // Publishes bytes on a channel. Safe to call from any thread. Returns false on failure.
  virtual bool Publish(const std::string& channel, const void* data, size_t size) = 0;
};

class Transport : public Publisher {
 public:
  // Registers a handler for one channel (exact name). Call before handling starts.
  virtual void Subscribe(const std::string& channel, RawHandler handler) = 0;
  // Waits up to timeout_ms for messages and dispatches them on the calling thread.
  // Returns > 0 when a message was handled, 0 on timeout, < 0 on error or end of input.
  virtual int HandleTimeout(int timeout_ms) = 0;
};

// Encodes an lcm-gen message and publishes it. Returns false when encoding fails.
template <class Message>
bool PublishMessage(Publisher& publisher, const std::string& channel, const Message& message) {
  const int size = message.getEncodedSize();
  if (size < 0) return false;
  std::string buffer(static_cast<size_t>(size), '\0');
  if (message.encode(buffer.data(), 0, size) != size) return false;
  return publisher.Publish(channel, buffer.data(), buffer.size());
}

}  // namespace mfp
