#pragma once
#include <optional>
#include <string>

#include "meadow/capture/intrinsics.h"
#include "meadow/core/enum_names.h"

namespace meadow::capture {

// Unit of the integers stored in a depth PNG. Frames in memory are always millimetres.
enum class DepthUnit { Millimetre, FifthMillimetre /* TUM RGB-D: 1/5000 m */, Metre };

inline constexpr EnumNames<DepthUnit, 3> kDepthUnitNames{{{
    {DepthUnit::Millimetre, "mm"},
    {DepthUnit::FifthMillimetre, "0.2mm"},
    {DepthUnit::Metre, "m"},
}}};
// Parses "mm", "0.2mm", "m"; nullopt otherwise.
inline std::optional<DepthUnit> parseDepthUnit(const std::string& text) {
    return kDepthUnitNames.parse(text);
}
inline std::string toString(DepthUnit unit) { return std::string(kDepthUnitNames.name(unit)); }
// Millimetres per stored integer step.
double millimetresPerUnit(DepthUnit unit);

// What recording.json holds (see docs/formats.md#recording).
struct RecordingInfo {
    std::string sensor = "unknown";
    Intrinsics intrinsics;
    DepthUnit depthUnit = DepthUnit::Millimetre;
    int frameCount = 0;
    double frameRate_hz = 30.0;
};

}  // namespace meadow::capture
