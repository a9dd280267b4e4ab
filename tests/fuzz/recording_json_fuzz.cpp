// recording.json (capture/src/recording_json.cpp): any bytes, as the file's text.
#include "fuzz_target.h"
#include "recording_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return meadow::fuzz::readOrRefuse([&] {
        (void)meadow::capture::detail::recordingInfoFromJson(meadow::fuzz::text(data, size),
                                                             "fuzz/recording.json");
    });
}
