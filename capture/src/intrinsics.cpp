#include "meadow/capture/intrinsics.h"

#include <cmath>

namespace meadow::capture {

std::string Intrinsics::problem() const {
    if (width_px <= 0) return "width_px must be positive, got " + std::to_string(width_px);
    if (height_px <= 0) return "height_px must be positive, got " + std::to_string(height_px);
    const struct {
        const char* name;
        float value;
        bool mustBePositive;
    } fields[] = {{"fx_px", fx_px, true},
                  {"fy_px", fy_px, true},
                  {"cx_px", cx_px, false},
                  {"cy_px", cy_px, false}};
    for (const auto& f : fields) {
        if (!std::isfinite(f.value)) return std::string(f.name) + " is not a finite number";
        if (f.mustBePositive && f.value <= 0.f)
            return std::string(f.name) + " must be positive, got " + std::to_string(f.value);
    }
    return {};
}

bool operator==(const Intrinsics& a, const Intrinsics& b) {
    return a.width_px == b.width_px && a.height_px == b.height_px && a.fx_px == b.fx_px &&
           a.fy_px == b.fy_px && a.cx_px == b.cx_px && a.cy_px == b.cy_px;
}

}  // namespace meadow::capture
