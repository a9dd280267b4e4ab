// A depth frame's PNG (capture/src/depth_png.cpp): any bytes, as the file's contents.
#include <vector>

#include "depth_png.h"
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return meadow::fuzz::readOrRefuse([&] {
        const std::vector<unsigned char> bytes(data, data + size);
        (void)meadow::capture::detail::decodeDepthPng(bytes, "fuzz/000000.png");
    });
}
