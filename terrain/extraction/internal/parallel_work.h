#pragma once
// Independent items of the extraction on a few threads, the results kept in the order a
// single thread would make them: items are handed out in increasing order, each writes
// only its own slot, and every thread is joined before the call returns (no thread
// outlives an extraction; the daemon's map thread adds at most threads - 1 while it runs).
#include <algorithm>
#include <functional>

namespace mfp {

// Runs work(i) for every i in [0, n): on the calling thread and up to threads - 1 threads
// started here. work must be safe to run concurrently for different i and may return
// early on its own stop condition. When a call throws, no later item starts and the first
// exception is rethrown after the join. When no thread can be started, the calling thread
// does all the items.
void ParallelFor(int n, int threads, const std::function<void(int)>& work);

// A grid layer's passes are shared between the threads as bands of whole rows of about
// this many cells: bands enough to share one large layer, few enough that a band's
// bookkeeping is small against its cells. The results do not depend on it (each band
// writes only its own slot), only how evenly the threads share the work.
constexpr int kBandCells = 1 << 16;

// Rows of such a band in a grid `cols` cells wide (at least one).
inline int BandRows(int cols) { return std::max(1, kBandCells / std::max(1, cols)); }

}  // namespace mfp
