#pragma once
// Memory for frame after frame: a process that segments frames one after another should call
// keepFrameBuffersResident() once at its start (the `meadow` command and the benchmarks do).

namespace meadow::capture {

// Asks glibc's allocator to keep freed memory for the next frame instead of handing it back to
// the system: each frame allocates and frees frame-sized buffers (0.3-1.2 MB), and by default
// glibc trims the top of its heap, or maps such buffers afresh, so every frame faults those
// pages back in. Holds on to at most 64 MB of freed memory. Returns whether the allocator took
// the settings (false where it is not glibc's).
bool keepFrameBuffersResident();

}  // namespace meadow::capture
