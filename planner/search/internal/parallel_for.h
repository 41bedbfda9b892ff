#pragma once
// Runs task(0 .. count-1) at once: task(0) on the calling thread, task(k) for k >= 1 on a
// thread of its own; returns when all are done. The branch-and-bound's workers.
#include <thread>
#include <vector>

namespace mfp {

template <typename Task>
void ForEachInParallel(int count, const Task& task) {
  std::vector<std::thread> threads;
  for (int k = 1; k < count; ++k) threads.emplace_back([&task, k] { task(k); });
  if (count > 0) task(0);
  for (std::thread& t : threads) t.join();
}

}  // namespace mfp
