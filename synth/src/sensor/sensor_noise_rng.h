#pragma once
// The simulated sensor's random numbers: one counter-based stream per noise term and pixel
// (meadow::CounterRng), so a frame does not depend on loop order or threading, and switching one
// noise term on or off leaves the draws of every other term unchanged.
#include <cstdint>

#include "meadow/core/random.h"

namespace meadow::synth::detail {

// One stream per noise term; the values are part of the seed contract (changing them changes
// every simulated frame), so only ever append.
enum class NoiseStream : std::uint64_t {
    Lateral = 1,
    FlyingPixel = 2,
    Axial = 3,
    LateralField = 4,  // the white noise a correlated lateral field is smoothed from
};

class PixelRng : public CounterRng {
public:
    PixelRng(std::uint64_t seed, NoiseStream stream, std::uint64_t pixelIndex)
        : CounterRng(seed, static_cast<std::uint64_t>(stream), pixelIndex) {}
};

}  // namespace meadow::synth::detail
