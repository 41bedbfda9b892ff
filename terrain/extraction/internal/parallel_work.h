#pragma once
// Independent items of the extraction on a few threads, the results kept in the order a
// single thread would make them: items are handed out in increasing order, each writes
// only its own slot, and every thread is joined before the call returns (no thread
// outlives an extraction; the daemon's map thread adds at most threads - 1 while it runs).
#include <functional>

namespace mfp {

// Runs work(i) for every i in [0, n): on the calling thread and up to threads - 1 threads
// started here. work must be safe to run concurrently for different i and may return
// early on its own stop condition. When a call throws, no later item starts and the first
// exception is rethrown after the join. When no thread can be started, the calling thread
// does all the items.
void ParallelFor(int n, int threads, const std::function<void(int)>& work);

}  // namespace mfp
