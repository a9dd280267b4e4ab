// Parsing of the options that describe a plain PNG folder (--intrinsics).
#include <charconv>
#include <cmath>
#include <limits>
#include <vector>

#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"

namespace meadow::capture {

namespace {

const char* kIntrinsicsForm =
    "expected four numbers fx,fy,cx,cy in pixels, e.g. --intrinsics 525,525,319.5,239.5";

std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    const auto last = text.find_last_not_of(" \t");
    return text.substr(first, last - first + 1);
}

// Out-of-range values become infinity so that Intrinsics::problem() reports them.
float toFloat(double value) {
    if (std::isnan(value)) return std::numeric_limits<float>::quiet_NaN();
    if (std::abs(value) > std::numeric_limits<float>::max())
        return std::copysign(std::numeric_limits<float>::infinity(), value);
    return static_cast<float>(value);
}

}  // namespace

Intrinsics parseIntrinsics(const std::string& fx_fy_cx_cy) {
    const auto fail = [&](const std::string& what) -> Intrinsics {
        throw CaptureError("--intrinsics \"" + fx_fy_cx_cy + "\": " + what + "; " +
                           kIntrinsicsForm);
    };
    std::vector<float> values;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = fx_fy_cx_cy.find(',', start);
        const std::string part = trimmed(fx_fy_cx_cy.substr(
            start, comma == std::string::npos ? std::string::npos : comma - start));
        double value = 0.0;
        const char* end = part.data() + part.size();
        const auto [ptr, ec] = std::from_chars(part.data(), end, value);
        if (part.empty() || ec == std::errc::invalid_argument || ptr != end)
            return fail("\"" + part + "\" is not a number");
        if (ec == std::errc::result_out_of_range) value = std::numeric_limits<double>::infinity();
        values.push_back(toFloat(value));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (values.size() != 4) return fail("got " + std::to_string(values.size()) + " numbers");

    Intrinsics k;
    k.fx_px = values[0];
    k.fy_px = values[1];
    k.cx_px = values[2];
    k.cy_px = values[3];
    // The size is not known yet (it is the first frame's): what needs it is checked then.
    if (const std::string problem = k.numbersProblem(); !problem.empty()) return fail(problem);
    k.width_px = k.height_px = 0;
    return k;
}

}  // namespace meadow::capture
