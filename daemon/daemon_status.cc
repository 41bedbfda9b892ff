// DaemonCore's status_t: its state and counters, as the heartbeat publishes them.
#include "daemon/daemon_core.h"

#include <sstream>
#include <utility>

namespace mfp {
namespace {

// The counters status_t shows as they are, each with the DaemonCounters field it shows.
constexpr std::pair<int64_t status_t::*, int64_t DaemonCounters::*> kCounterFields[] = {
    {&status_t::requests, &DaemonCounters::requests},
    {&status_t::plans, &DaemonCounters::plans},
    {&status_t::rejected_messages, &DaemonCounters::rejected_messages},
    {&status_t::invalid_requests, &DaemonCounters::invalid_requests},
    {&status_t::dropped_requests, &DaemonCounters::dropped_requests},
    {&status_t::maps, &DaemonCounters::maps},
    {&status_t::rejected_maps, &DaemonCounters::rejected_maps},
    {&status_t::superseded_requests, &DaemonCounters::superseded_requests},
    {&status_t::expired_requests, &DaemonCounters::expired_requests},
    {&status_t::time_limit_endings, &DaemonCounters::time_limit_endings},
    {&status_t::abandoned_solves, &DaemonCounters::abandoned_solves},
    {&status_t::inbox_overflows, &DaemonCounters::inbox_overflows},
    {&status_t::superseded_maps, &DaemonCounters::superseded_maps},
    {&status_t::empty_maps, &DaemonCounters::empty_maps},
    {&status_t::publish_failures, &DaemonCounters::publish_failures},
    {&status_t::internal_errors, &DaemonCounters::internal_errors},
};

}  // namespace

void DaemonCore::SetUdpErrorSource(std::function<int64_t()> source) {
  std::lock_guard<std::mutex> lock(mutex_);
  udp_errors_ = std::move(source);
}

status_t DaemonCore::StatusMessage() const {
  const int64_t now = clock_();
  std::function<int64_t()> udp_errors;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    udp_errors = udp_errors_;
  }
  const int64_t udp = udp_errors ? udp_errors() : -1;
  std::lock_guard<std::mutex> lock(mutex_);
  status_t s;
  s.utime = now;
  // Copies of the constants: lcm-gen declares them without a definition to bind to.
  const int8_t no_map = status_t::STATE_NO_MAP, planning = status_t::STATE_PLANNING,
               idle = status_t::STATE_IDLE;
  s.state = regions_ == nullptr ? no_map : planning_ ? planning : idle;
  for (const auto& [shown, counted] : kCounterFields) s.*shown = counters_.*counted;
  s.queue_length = static_cast<int32_t>(queue_.size() + received_.size());
  s.num_regions = regions_ == nullptr ? 0 : static_cast<int32_t>(regions_->size());
  s.last_solve_time_s = counters_.last_solve_time_s;
  s.map_age_s = regions_ == nullptr ? -1.0 : 1e-6 * static_cast<double>(now - map_receive_utime_);
  s.uptime_s = 1e-6 * static_cast<double>(now - start_utime_);
  s.udp_receive_errors = udp;
  s.extracting_map = extracting_;
  std::ostringstream msg;
  msg << (regions_ == nullptr ? "waiting for a map" : planning_ ? "planning" : "idle")
      << (extracting_ ? ", extracting a map" : "") << "; requests " << s.requests << ", plans "
      << s.plans << ", rejected messages " << s.rejected_messages << ", invalid "
      << s.invalid_requests << ", dropped " << s.dropped_requests << ", superseded "
      << s.superseded_requests << ", expired " << s.expired_requests << ", time limit "
      << s.time_limit_endings << ", intake overflows " << s.inbox_overflows
      << ", publish failures " << s.publish_failures << ", internal errors "
      << counters_.internal_errors;
  s.message = msg.str();
  return s;
}

void DaemonCore::PublishStatus() { Publish(kStatusChannel, StatusMessage()); }

}  // namespace mfp
