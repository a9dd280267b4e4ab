// The archetype library JSON (modeling/src/archetype_library.cpp): any bytes, as the file's text.
#include "fuzz_target.h"
#include "meadow/modeling/archetype_library.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return meadow::fuzz::readOrRefuse([&] {
        (void)meadow::modeling::parseArchetypeLibrary(meadow::fuzz::text(data, size),
                                                      "fuzz/lib.json");
    });
}
