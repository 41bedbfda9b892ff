#pragma once
// Work on a thread of its own that the caller may stop waiting for: at a deadline, or
// when a stop flag is raised. The thread is detached and owns everything it touches
// (the work function's captures and the shared result slot), so an abandoned task runs
// to its end harmlessly and the waiting thread answers on time. The work should check a
// stop flag the caller sets when it stops waiting (the daemon's plans do: Deadline), so
// an abandoned task ends soon; a counter of running tasks lets the caller bound how many
// abandoned ones it leaves behind.
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

// Starts `body` on a thread of its own that nobody joins. Throws (std::system_error from
// std::thread) when no thread can be created. Replaceable for tests and embedders.
using TaskLauncher = std::function<void(std::function<void()> body)>;
inline void LaunchDetachedThread(std::function<void()> body) { std::thread(std::move(body)).detach(); }

template <class Result>
class AbandonableTask {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;

  // Starts `work` through `launcher`. `running` (optional) counts the tasks whose work
  // has not yet returned: raised here, lowered by the task's thread as its last act.
  // Throws what the launcher throws (no thread: nothing runs, `running` is unchanged).
  explicit AbandonableTask(std::function<Result()> work, std::shared_ptr<std::atomic<int>> running = nullptr,
                           const TaskLauncher& launcher = LaunchDetachedThread)
      : state_(std::make_shared<State>()) {
    if (running) running->fetch_add(1);
    try {
      launcher([state = state_, work = std::move(work), running] {
        std::optional<Result> result;
        std::exception_ptr error;
        try {
          result.emplace(work());
        } catch (...) {
          error = std::current_exception();
        }
        {
          std::lock_guard<std::mutex> lock(state->mutex);
          state->result = std::move(result);
          state->error = error;
          state->done = true;
          state->finished.notify_all();
        }
        if (running) running->fetch_sub(1);
      });
    } catch (...) {
      if (running) running->fetch_sub(1);
      throw;
    }
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
