#pragma once
// Work on a thread of its own that the caller may stop waiting for: at a deadline, or
// when a stop flag is raised. The thread is detached and owns everything it touches
// (the work function's captures and the shared result slot), so an abandoned task runs
// to its end harmlessly and the waiting thread answers on time. The daemon uses it for
// plans and map extractions, whose solvers do not yet check a stop flag themselves.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

namespace mfp {

template <class Result>
class AbandonableTask {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;

  explicit AbandonableTask(std::function<Result()> work) : state_(std::make_shared<State>()) {
    std::thread([state = state_, work = std::move(work)] {
      std::optional<Result> result;
      std::exception_ptr error;
      try {
        result.emplace(work());
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(state->mutex);
      state->result = std::move(result);
      state->error = error;
      state->done = true;
      state->finished.notify_all();
    }).detach();
  }

  // Waits until the work has finished (returns its result, or rethrows what it threw),
  // `until` has passed or `stop` is raised (both: nullopt; the work goes on unobserved).
  // `stop` is polled every few milliseconds.
  std::optional<Result> Wait(TimePoint until, const std::atomic<bool>& stop) {
    std::unique_lock<std::mutex> lock(state_->mutex);
    for (;;) {
      if (state_->done) {
        if (state_->error) std::rethrow_exception(state_->error);
        return std::move(state_->result);
      }
      if (stop.load() || std::chrono::steady_clock::now() >= until) return std::nullopt;
      const TimePoint poll = std::chrono::steady_clock::now() + std::chrono::milliseconds(5);
      state_->finished.wait_until(lock, std::min(poll, until));
    }
  }

 private:
  struct State {
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::optional<Result> result;
    std::exception_ptr error;
  };
  std::shared_ptr<State> state_;
};

}  // namespace mfp
