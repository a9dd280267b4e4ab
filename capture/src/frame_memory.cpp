// glibc's malloc tuning for a frame loop (frame_memory.h).
#include "meadow/capture/frame_memory.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace meadow::capture {

namespace {
// Freed memory at the top of the heap beyond this is returned to the system.
constexpr int kTrimThreshold_bytes = 64 << 20;
// Allocations from this size on are mapped on their own (glibc's largest dynamic threshold on
// 64-bit): frame buffers stay below it and come from the heap.
constexpr int kMmapThreshold_bytes = 32 << 20;
}  // namespace

bool keepFrameBuffersResident() {
#if defined(__GLIBC__)
    // mallopt returns 1 on success.
    return mallopt(M_TRIM_THRESHOLD, kTrimThreshold_bytes) == 1 &&
           mallopt(M_MMAP_THRESHOLD, kMmapThreshold_bytes) == 1;
#else
    return false;
#endif
}

}  // namespace meadow::capture
