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

class LcmTransport final : public Transport {
 public:
  // Throws InputError when LCM cannot be created for the URL.
  explicit LcmTransport(const std::string& url);
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
  lcm_t* lcm_ = nullptr;
  std::mutex publish_mutex_;
  // Handlers by channel; node-based so pointers given to LCM stay valid.
  std::map<std::string, std::unique_ptr<RawHandler>> handlers_;
};

}  // namespace mfp
