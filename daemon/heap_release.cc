#include "daemon/heap_release.h"

#include <cstdlib>  // defines __GLIBC__ with glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mfp {
namespace {

// Above glibc's starting mmap threshold (128 KiB): the planner's larger matrices stay on
// the heap; a map's buffers and the largest factorisations are mmapped [bytes].
constexpr int kHeapMmapThresholdBytes = 1 << 20;
// An arena's free top kept at most [bytes]: a plan's working set is reused, not given
// back and faulted in again at every plan.
constexpr int kHeapTrimThresholdBytes = 4 << 20;

}  // namespace

void BoundHeapRetention() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, kHeapMmapThresholdBytes);
  mallopt(M_TRIM_THRESHOLD, kHeapTrimThresholdBytes);
#endif
}

void ReleaseFreeHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace mfp
