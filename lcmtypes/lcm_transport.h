#pragma once
// Transport over an LCM provider URL: udpm://, memq:// (in-process), or file:// (read
// a log as input; writes go to the log in write mode).
#include <lcm/lcm.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "lcmtypes/transport.h"

namespace mfp {

// A udpm:// URL with the option recv_buf_size=BYTES (the socket receive buffer, which
// must hold every fragment of the largest message); an option already in the URL and
// any other provider are left as they are.
std::string WithReceiveBuffer(const std::string& url, size_t bytes);

class LcmTransport final : public Transport {
 public:
  // Throws InputError when LCM cannot be created for the URL. queue_capacity: messages
  // LCM keeps per subscribed channel before it discards (LCM's own default is 30).
  explicit LcmTransport(const std::string& url, int queue_capacity = 30);
  ~LcmTransport() override;
  LcmTransport(const LcmTransport&) = delete;
  LcmTransport& operator=(const LcmTransport&) = delete;

  bool Publish(const std::string& channel, const void* data, size_t size) override;
  void Subscribe(const std::string& channel, RawHandler handler) override;
  int HandleTimeout(int timeout_ms) override;

  const std::string& url() const { return url_; }

 private:
  static void OnMessage(const lcm_recv_buf_t* rbuf, const char* channel, void* user);

  std::string url_;
  int queue_capacity_;
  lcm_t* lcm_ = nullptr;
  std::mutex publish_mutex_;
  // Handlers by channel; node-based so pointers given to LCM stay valid.
  std::map<std::string, std::unique_ptr<RawHandler>> handlers_;
};

}  // namespace mfp
