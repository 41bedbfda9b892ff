#include "lcmtypes/lcm_transport.h"

#include "base/check.h"

namespace mfp {

std::string WithReceiveBuffer(const std::string& url, size_t bytes) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos) return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") +
         "recv_buf_size=" + std::to_string(bytes);
}

LcmTransport::LcmTransport(const std::string& url, int queue_capacity)
    : url_(url), queue_capacity_(queue_capacity) {
  MFP_CHECK(queue_capacity > 0);
  lcm_ = lcm_create(url.c_str());
  if (lcm_ == nullptr) throw InputError("lcm_url: LCM could not be created for '" + url + "'");
}

LcmTransport::~LcmTransport() { lcm_destroy(lcm_); }

bool LcmTransport::Publish(const std::string& channel, const void* data, size_t size) {
  if (size > static_cast<size_t>(INT32_MAX)) return false;
  std::lock_guard<std::mutex> lock(publish_mutex_);
  return lcm_publish(lcm_, channel.c_str(), data, static_cast<unsigned int>(size)) == 0;
}

void LcmTransport::Subscribe(const std::string& channel, RawHandler handler) {
  MFP_CHECK_MSG(handlers_.count(channel) == 0, "one handler per channel: " + channel);
  auto& slot = handlers_[channel];
  slot = std::make_unique<RawHandler>(std::move(handler));
  // LCM treats the channel as a regular expression; anchor it to the exact name.
  lcm_subscription_t* subscription = lcm_subscribe(lcm_, ("^" + channel + "$").c_str(),
                                                   &LcmTransport::OnMessage, slot.get());
  MFP_CHECK_MSG(subscription != nullptr, "lcm_subscribe failed for " + channel);
  MFP_CHECK(lcm_subscription_set_queue_capacity(subscription, queue_capacity_) == 0);
}

int LcmTransport::HandleTimeout(int timeout_ms) { return lcm_handle_timeout(lcm_, timeout_ms); }

void LcmTransport::OnMessage(const lcm_recv_buf_t* rbuf, const char* channel, void* user) {
  const auto* handler = static_cast<const RawHandler*>(user);
  RawMessage message;
  message.channel = channel;
  message.data = static_cast<const uint8_t*>(rbuf->data);
  message.size = rbuf->data_size;
  message.receive_utime = rbuf->recv_utime;
  (*handler)(message);
}

}  // namespace mfp
