// The scene JSON (runtime/src/scene.cpp): any bytes, as the file's text. Files it names are
// looked up beside a folder that does not exist, so every reference is refused.
#include "fuzz_target.h"
#include "meadow/runtime/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return meadow::fuzz::readOrRefuse([&] {
        (void)meadow::runtime::parseSceneDescription(meadow::fuzz::text(data, size),
                                                     "/nonexistent/meadow-fuzz/scene.json");
    });
}
