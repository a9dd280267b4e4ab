// The synth truth JSON (synth/src/synthesize.cpp): any bytes, as the file's text.
#include "fuzz_target.h"
#include "meadow/synth/synthesize.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return meadow::fuzz::readOrRefuse([&] {
        (void)meadow::synth::parseSynthTruth(meadow::fuzz::text(data, size), "fuzz/blades.json");
    });
}
