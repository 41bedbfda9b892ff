#pragma once
// A point in time a piece of work must end by, and optionally a stop flag that ends it
// sooner: the one object long-running code checks (solvers inside their iterations,
// the search between nodes, the region extractor between patches). Expired() is true
// once the clock passes the deadline or another thread sets the flag. Cheap to copy and
// to check (a clock read and an atomic load). A default Deadline never expires.
//
// A stop flag (SIGTERM, a superseding request) is a std::atomic<bool> owned by the caller
// that outlives the work: Deadline::After(limit).WithStop(&flag), and set the flag from
// any thread to end the work at its next check.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>

namespace mfp {

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;

  Deadline() = default;  // never, no stop flag
  static Deadline After(double seconds) {
    Deadline d;
    d.finite_ = true;
    d.at_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(std::max(seconds, 0.0)));
    return d;
  }
  // This deadline, also ended by *stop (null: no flag).
  Deadline WithStop(const std::atomic<bool>* stop) const {
    Deadline d = *this;
    d.stop_ = stop;
    return d;
  }
  // The sooner of this deadline and `seconds` from now, with this one's stop flag.
  Deadline Within(double seconds) const {
    const Deadline other = After(seconds);
    Deadline d = *this;
    if (!finite_ || other.at_ < at_) {
      d.finite_ = true;
      d.at_ = other.at_;
    }
    return d;
  }

  // This deadline moved `seconds` later (a never-expiring one stays so), with this one's
  // stop flag: for a short piece of work that must finish what an expired search began,
  // bounded past the request's deadline by `seconds` and still ended by the flag.
  Deadline ExtendedBy(double seconds) const {
    Deadline d = *this;
    if (finite_) {
      d.at_ += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::max(seconds, 0.0)));
    }
    return d;
  }

  bool Stopped() const { return stop_ != nullptr && stop_->load(std::memory_order_relaxed); }
  bool Expired() const { return Stopped() || (finite_ && Clock::now() >= at_); }
  // Seconds left (0 when expired or stopped; +infinity when it never expires).
  double RemainingSeconds() const {
    if (Stopped()) return 0.0;
    if (!finite_) return std::numeric_limits<double>::infinity();
    return std::max(0.0, std::chrono::duration<double>(at_ - Clock::now()).count());
  }
  bool finite() const { return finite_; }
  const std::atomic<bool>* stop_flag() const { return stop_; }

 private:
  bool finite_ = false;
  Clock::time_point at_{};
  const std::atomic<bool>* stop_ = nullptr;
};

}  // namespace mfp
