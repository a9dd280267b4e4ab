#include "option_checks.h"

#include <cmath>
#include <sstream>

namespace meadow::cli {

CLI::Validator finiteRange(double min, double max) {
    std::ostringstream range;
    range << "in [" << min << ", " << max << "]";
    const std::string description = range.str();
    return CLI::Validator(
        [min, max, description](std::string& text) {
            double value = 0.0;
            try {
                std::size_t used = 0;
                value = std::stod(text, &used);
                if (used != text.size()) return "not a number: " + text;
            } catch (const std::exception&) {
                return "not a number: " + text;
            }
            if (!std::isfinite(value)) return "must be a finite number, got " + text;
            if (value < min || value > max) return "out of range " + description + ": " + text;
            return std::string();
        },
        description);
}

}  // namespace meadow::cli
