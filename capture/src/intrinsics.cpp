#include "meadow/capture/intrinsics.h"

#include <cmath>
#include <sstream>

namespace meadow::capture {

namespace {

constexpr int kMaxSide_px = 16384;
constexpr double kMinFieldOfView_deg = 1.0;
constexpr double kMaxFieldOfView_deg = 170.0;

std::string shortText(float value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

}  // namespace

std::string Intrinsics::problem() const {
    if (std::string why = numbersProblem(); !why.empty()) return why;
    if (width_px <= 0) return "width_px must be positive, got " + std::to_string(width_px);
    if (height_px <= 0) return "height_px must be positive, got " + std::to_string(height_px);
    return plausibilityProblem();
}

std::string Intrinsics::numbersProblem() const {
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

std::string Intrinsics::plausibilityProblem() const {
    if (width_px > kMaxSide_px || height_px > kMaxSide_px)
        return "the image is " + std::to_string(width_px) + "x" + std::to_string(height_px) +
               " px, more than any depth camera's " + std::to_string(kMaxSide_px) + " px a side";
    // A focal length is a physical quantity: in pixels it gives a field of view across the
    // image, and no camera sees less than a degree or more than 170 degrees.
    const auto fieldOfView_deg = [](float side_px, float f_px) {
        return 2.0 * std::atan(0.5 * side_px / f_px) * 180.0 / 3.14159265358979;
    };
    const struct {
        const char* name;
        float focal_px;
        int side_px;
    } focals[] = {{"fx_px", fx_px, width_px}, {"fy_px", fy_px, height_px}};
    for (const auto& f : focals) {
        const double fov_deg = fieldOfView_deg(static_cast<float>(f.side_px), f.focal_px);
        if (fov_deg < kMinFieldOfView_deg || fov_deg > kMaxFieldOfView_deg)
            return std::string(f.name) + " " + shortText(f.focal_px) +
                   " gives a field of view of " + shortText(static_cast<float>(fov_deg)) +
                   " deg across " + std::to_string(f.side_px) +
                   " px: focal lengths are in pixels (a Kinect's is " + "about 575)";
    }
    // The principal point lies in the image, or near it for a cropped one.
    if (cx_px < -0.5f * width_px || cx_px > 1.5f * width_px)
        return "cx_px " + shortText(cx_px) + " lies far outside the " + std::to_string(width_px) +
               "-px-wide image: the principal point is in pixels (about width / 2)";
    if (cy_px < -0.5f * height_px || cy_px > 1.5f * height_px)
        return "cy_px " + shortText(cy_px) + " lies far outside the " + std::to_string(height_px) +
               "-px-high image: the principal point is in pixels (about height / 2)";
    return {};
}

bool operator==(const Intrinsics& a, const Intrinsics& b) {
    return a.width_px == b.width_px && a.height_px == b.height_px && a.fx_px == b.fx_px &&
           a.fy_px == b.fy_px && a.cx_px == b.cx_px && a.cy_px == b.cy_px;
}

}  // namespace meadow::capture
