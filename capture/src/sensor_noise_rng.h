#pragma once
// Counter-based random numbers for the simulated sensor: every (seed, term, pixel) triple has
// its own independent stream, so a frame does not depend on loop order or threading, and
// switching one noise term on or off leaves the draws of every other term unchanged.
#include <cmath>
#include <cstdint>
#include <numbers>

namespace meadow::capture::detail {

// One stream per noise term; the values are part of the seed contract (changing them changes
// every simulated frame), so only ever append.
enum class NoiseStream : std::uint64_t {
    Lateral = 1,
    FlyingPixel = 2,
    Axial = 3,
};

// SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators"):
// a Weyl sequence through a strong 64-bit finaliser; passes BigCrush, cheap to seed per pixel.
class PixelRng {
public:
    PixelRng(std::uint64_t seed, NoiseStream stream, std::uint64_t pixelIndex) {
        std::uint64_t s = seed;
        std::uint64_t key = next(s);
        key ^= static_cast<std::uint64_t>(stream) * kStreamMultiplier;
        key ^= pixelIndex * kPixelMultiplier;
        state_ = key;
        (void)next();  // decorrelates neighbouring pixel indices
    }

    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

    // Standard normal by Box-Muller; 1 - uniform() is in (0, 1], so the log is finite.
    double normal() {
        const double u1 = 1.0 - uniform();
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    }

private:
    // Odd constants with well-mixed bits (from the golden ratio and from PCG's multipliers),
    // so that streams and pixel indices land far apart in the key space.
    static constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ull;
    static constexpr std::uint64_t kStreamMultiplier = 0xD1B54A32D192ED03ull;
    static constexpr std::uint64_t kPixelMultiplier = 0xABC98388FB8FAC03ull;

    static std::uint64_t next(std::uint64_t& state) {
        std::uint64_t z = (state += kGolden);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;  // SplitMix64 finaliser constants
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::uint64_t next() { return next(state_); }

    std::uint64_t state_ = 0;
};

}  // namespace meadow::capture::detail
