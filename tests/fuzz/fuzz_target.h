#pragma once
// libFuzzer entry points for meadow's readers. A reader given any bytes either returns or throws
// meadow::Error (one clear line for the user); anything else that escapes, and every crash,
// leak or undefined behaviour the sanitizers see, is a defect the fuzzer reports.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "meadow/core/error.h"

namespace meadow::fuzz {

template <class F>
int readOrRefuse(F&& read) {
    try {
        read();
    } catch (const Error&) {
        // A refusal with a message: what the reader must do with bad input.
    } catch (const std::exception& e) {
        std::fprintf(stderr, "not a meadow::Error: %s\n", e.what());
        std::abort();
    }
    return 0;
}

inline std::string text(const std::uint8_t* data, std::size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace meadow::fuzz
