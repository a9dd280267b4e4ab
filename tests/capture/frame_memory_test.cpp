// keepFrameBuffersResident (frame_memory.h): a frame-sized buffer freed and allocated again
// comes back without fresh pages from the system.
#include "meadow/capture/frame_memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstring>
#include <iostream>
#include <memory>

namespace meadow::capture {
namespace {

long minorFaults() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}

TEST(FrameMemory, AFreedFrameBufferIsReusedWithoutPageFaults) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer brings its own allocator";
#else
    ASSERT_TRUE(keepFrameBuffersResident()) << "glibc refused the settings";
    // A 640 x 480 x 4-byte buffer: 300 pages. With glibc's defaults (such a buffer mapped on
    // its own, or the heap's top trimmed after it is freed) these rounds fault on every page.
    constexpr std::size_t kBytes = 640 * 480 * 4;
    constexpr int kRounds = 10;
    {
        auto warm = std::make_unique<unsigned char[]>(kBytes);
        std::memset(warm.get(), 1, kBytes);
    }
    const long before = minorFaults();
    for (int round = 0; round < kRounds; ++round) {
        auto buffer = std::make_unique<unsigned char[]>(kBytes);
        std::memset(buffer.get(), round, kBytes);  // touch every page
    }
    const long faults = minorFaults() - before;
    std::cout << "  " << faults << " page faults over " << kRounds << " rounds of " << kBytes
              << " bytes\n";
    EXPECT_LT(faults, 30);  // a tenth of one round's pages
#endif
}

}  // namespace
}  // namespace meadow::capture
