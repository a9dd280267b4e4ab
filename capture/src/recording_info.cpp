#include "meadow/capture/recording_info.h"

namespace meadow::capture {

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
