#pragma once
// Bounding the memory glibc keeps after a map and after each plan. Both run on threads of
// their own (a map's extraction allocates tens of MiB for a moment; a plan on a field of
// hundreds of regions several), and glibc keeps what such a thread frees in its arena:
// by default a large free raises the mmap and trim thresholds (up to 32 and 64 MiB), so
// the free top of a thread's arena was never given back, and malloc_trim gives back the
// free chunks of every arena but the free top of the main one only. On the 577-region
// soak field the process held 40-60 MiB so (1-2 MiB in use; docs/measurements.md).

namespace mfp {

// Fixed thresholds for a long-running process (glibc mallopt; nothing with another C
// library): blocks of kHeapMmapThresholdBytes and more are mmapped (given back when
// freed), and an arena's free top beyond kHeapTrimThresholdBytes is given back at the
// free that makes it. Call once at start, before the threads.
void BoundHeapRetention();

// Returns the free chunks of every malloc arena to the system (glibc malloc_trim; nothing
// with another C library). Takes milliseconds: call it after a reply, not before.
void ReleaseFreeHeap();

}  // namespace mfp
