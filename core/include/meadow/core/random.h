#pragma once
// meadow's one source of reproducible random numbers. The same seed gives the same numbers on
// every machine: the engines are specified bit for bit by the C++ standard and the uniform
// numbers are made here from their raw output (the std::*_distribution classes are not
// specified bit for bit).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace meadow {

// SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators"): a
// Weyl sequence through a strong 64-bit finaliser. Advances `state` and returns the next value;
// cheap to seed per pixel or per frame, and neighbouring seeds share nothing.
[[nodiscard]] constexpr std::uint64_t splitMix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);  // the golden ratio's Weyl step
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;         // SplitMix64 finaliser constants
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// A sequential generator (std::mt19937_64) for whatever draws one number after another:
// tufts, blade seeding, wind turbulence, shuffles.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : engine_(seed) {}

    // Uniform in [0, 1) from the top 24 bits of one draw (a float's mantissa).
    float uniform() { return static_cast<float>(engine_() >> 40) * 0x1.0p-24f; }
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    bool chance(float p) { return uniform() < p; }
    // Uniform over the integers lo..hi, both included.
    int integer(int lo, int hi) {
        return lo + static_cast<int>(uniform() * static_cast<float>(hi - lo + 1));
    }
    // Standard normal. std::normal_distribution's bits are the standard library's own: the
    // same with one library, not across libraries.
    float normal() { return normal_(engine_); }
    // For std::shuffle and the like.
    std::mt19937_64& engine() { return engine_; }

private:
    std::mt19937_64 engine_;
    std::normal_distribution<float> normal_{0.f, 1.f};
};

// Counter-based numbers: every (seed, stream, index) triple has its own independent sequence,
// so a result does not depend on loop order or threading, and switching one stream on or off
// leaves every other stream's draws unchanged (the simulated sensor's noise per pixel).
class CounterRng {
public:
    CounterRng(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
        std::uint64_t s = seed;
        std::uint64_t key = splitMix64(s);
        key ^= stream * kStreamMultiplier;
        key ^= index * kIndexMultiplier;
        state_ = key;
        (void)splitMix64(state_);  // decorrelates neighbouring indices
    }

    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(splitMix64(state_) >> 11) * 0x1.0p-53; }

    // Standard normal by Box-Muller; 1 - uniform() is in (0, 1], so the log is finite.
    double normal() {
        const double u1 = 1.0 - uniform();
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    }

private:
    // Odd constants with well-mixed bits (from PCG's multipliers), so that streams and indices
    // land far apart in the key space.
    static constexpr std::uint64_t kStreamMultiplier = 0xD1B54A32D192ED03ull;
    static constexpr std::uint64_t kIndexMultiplier = 0xABC98388FB8FAC03ull;

    std::uint64_t state_ = 0;
};

}  // namespace meadow
