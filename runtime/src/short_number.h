#pragma once
// Numbers in messages for people: 0, 0.97, 100000, 1e+06 (std::to_string writes 0.000000).
#include <sstream>
#include <string>

namespace meadow::runtime {

inline std::string shortNumber(double value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

}  // namespace meadow::runtime
