#pragma once
// Pinhole intrinsics in OpenCV's convention: x right, y down, z forward, metres; pixel centres
// at integer coordinates (cx = 319.5 centres a 640-pixel-wide image).
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>

namespace meadow::capture {

struct Intrinsics {
    int width_px = 640;
    int height_px = 480;
    float fx_px = 575.8f;
    float fy_px = 575.8f;
    float cx_px = 319.5f;
    float cy_px = 239.5f;

    // PrimeSense / Kinect v1 class depth camera, the simulated sensor's default.
    static Intrinsics kinectV1() { return {}; }

    // Image point (pixels) of a camera-space point (metres). Requires z > 0.
    [[nodiscard]] glm::vec2 project(const glm::vec3& cameraPoint_m) const {
        return {fx_px * cameraPoint_m.x / cameraPoint_m.z + cx_px,
                fy_px * cameraPoint_m.y / cameraPoint_m.z + cy_px};
    }
    // Camera-space point (metres) seen at pixel (u, v) at depth z (metres).
    [[nodiscard]] glm::vec3 backProject(float u_px, float v_px, float z_m) const {
        return {(u_px - cx_px) * z_m / fx_px, (v_px - cy_px) * z_m / fy_px, z_m};
    }
    // Empty when usable; otherwise what is wrong ("fx_px is NaN", "width_px is 0", a focal
    // length that gives no camera's field of view across the image, ...).
    [[nodiscard]] std::string problem() const;
    // The parts of problem() that need no image size: finite numbers, positive focal lengths.
    [[nodiscard]] std::string numbersProblem() const;
    // The parts that do: the image size, the field of view, the principal point in the image.
    [[nodiscard]] std::string plausibilityProblem() const;
};

bool operator==(const Intrinsics&, const Intrinsics&);

}  // namespace meadow::capture
