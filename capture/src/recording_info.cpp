#include "meadow/capture/recording_info.h"

namespace meadow::capture {

std::optional<DepthUnit> parseDepthUnit(const std::string& text) {
    if (text == "mm") return DepthUnit::Millimetre;
    if (text == "0.2mm") return DepthUnit::FifthMillimetre;
    if (text == "m") return DepthUnit::Metre;
    return std::nullopt;
}

std::string toString(DepthUnit unit) {
    switch (unit) {
        case DepthUnit::Millimetre:
            return "mm";
        case DepthUnit::FifthMillimetre:
            return "0.2mm";
        case DepthUnit::Metre:
            return "m";
    }
    return "mm";
}

double millimetresPerUnit(DepthUnit unit) {
    switch (unit) {
        case DepthUnit::Millimetre:
            return 1.0;
        case DepthUnit::FifthMillimetre:
            return 0.2;
        case DepthUnit::Metre:
            return 1000.0;
    }
    return 1.0;
}

}  // namespace meadow::capture
