#include "meadow/core/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace meadow {
namespace {

TEST(Rng, TheSameSeedGivesTheSameNumbersAndUniformStaysInItsRange) {
    Rng a(42), b(42), c(43);
    bool differs = false;
    for (int i = 0; i < 1000; ++i) {
        const float x = a.uniform();
        EXPECT_EQ(x, b.uniform());
        differs = differs || x != c.uniform();
        EXPECT_GE(x, 0.f);
        EXPECT_LT(x, 1.f);
        const int k = a.integer(3, 5);
        (void)b.integer(3, 5);
        (void)c.integer(3, 5);
        EXPECT_GE(k, 3);
        EXPECT_LE(k, 5);
    }
    EXPECT_TRUE(differs);
}

TEST(Rng, UniformNumbersComeFromTheEnginesRawBits) {
    // Specified bit for bit: the engine's first output's top 24 bits, as a fraction of 2^24.
    std::mt19937_64 engine(7);
    Rng rng(7);
    EXPECT_EQ(rng.uniform(), static_cast<float>(engine() >> 40) * 0x1.0p-24f);
}

TEST(Rng, NormalNumbersHaveUnitSpread) {
    Rng rng(5);
    constexpr int kDraws = 20000;
    double sum = 0.0, sumSq = 0.0;
    for (int i = 0; i < kDraws; ++i) {
        const double x = rng.normal();
        sum += x;
        sumSq += x * x;
    }
    const double mean = sum / kDraws;
    EXPECT_NEAR(mean, 0.0, 0.03);  // 4 standard errors of the mean
    EXPECT_NEAR(std::sqrt(sumSq / kDraws - mean * mean), 1.0, 0.03);
}

TEST(CounterRng, EachStreamAndIndexHasItsOwnSequence) {
    CounterRng a(1, 2, 3), same(1, 2, 3), otherStream(1, 3, 3), otherIndex(1, 2, 4);
    const double x = a.uniform();
    EXPECT_EQ(x, same.uniform());
    EXPECT_NE(x, otherStream.uniform());
    EXPECT_NE(x, otherIndex.uniform());
}

TEST(SplitMix64, MatchesTheReferenceSequence) {
    // Steele, Lea & Flood's SplitMix64 seeded with 0: the first outputs of the reference code.
    std::uint64_t state = 0;
    EXPECT_EQ(splitMix64(state), 0xE220A8397B1DCDAFull);
    EXPECT_EQ(splitMix64(state), 0x6E789E6AA1B965F4ull);
}

}  // namespace
}  // namespace meadow
