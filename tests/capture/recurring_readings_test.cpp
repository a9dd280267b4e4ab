// Recurring readings (recurring_readings.h): per pixel, the nearest depth that enough frames of a
// still tuft read within a few millimetres of one another, for the tip trails.
#include "meadow/capture/recurring_readings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <vector>

#include "meadow/capture/error.h"

namespace meadow::capture {
namespace {

constexpr std::uint16_t kWall_mm = 1500;
const cv::Point kTip{4, 3};  // the pixel the tests read

// `count` frames of a wall, with `tip` read at kTip in the first tip.size() frames.
std::vector<DepthFrame> frames(int count, const std::vector<std::uint16_t>& tip) {
    std::vector<DepthFrame> out(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        out[static_cast<std::size_t>(i)].depth_mm = cv::Mat1w(8, 10, kWall_mm);
        out[static_cast<std::size_t>(i)].index = i;
        if (static_cast<std::size_t>(i) < tip.size())
            out[static_cast<std::size_t>(i)].depth_mm(kTip) = tip[static_cast<std::size_t>(i)];
    }
    return out;
}

TEST(RecurringReadings, ATipReadInAQuarterOfTheFramesRecursAtItsDepth) {
    // A thin tip at 0.8 m read as blade in 3 of 12 frames, as the wall in the rest.
    const RecurringReadings r = recurringReadings(frames(12, {803, 798, 800}));
    EXPECT_EQ(r.frames, 12);
    EXPECT_EQ(r.neededFrames, 3);
    EXPECT_EQ(r.depth_mm(kTip), 800);  // the middle of the three
    EXPECT_EQ(r.depth_mm(0, 0), kWall_mm);
    EXPECT_EQ(r.recurringPixels, 80);
}

TEST(RecurringReadings, ReadingsThatDisagreeOrAreTooFewDoNotRecur) {
    // Flying pixels at scattered depths in 3 frames: the nearest agreeing run is the wall's.
    EXPECT_EQ(recurringReadings(frames(12, {700, 760, 820})).depth_mm(kTip), kWall_mm);
    // Two readings of the tip are not enough of 12 frames.
    EXPECT_EQ(recurringReadings(frames(12, {800, 801})).depth_mm(kTip), kWall_mm);
    // 24 frames need 6 (a quarter): 5 readings of the tip are not enough, 6 are.
    EXPECT_EQ(recurringReadings(frames(24, {800, 800, 800, 800, 800})).depth_mm(kTip), kWall_mm);
    EXPECT_EQ(recurringReadings(frames(24, {800, 800, 800, 800, 800, 800})).depth_mm(kTip), 800);
    // Fewer frames than the minimum: nothing recurs.
    const RecurringReadings two = recurringReadings(frames(2, {800, 800}));
    EXPECT_EQ(two.neededFrames, 3);
    EXPECT_EQ(cv::countNonZero(two.depth_mm), 0);
    EXPECT_EQ(two.recurringPixels, 0);
}

TEST(RecurringReadings, PixelsWithoutReadingsDoNotCount) {
    // The tip read in 3 frames, no reading (0) in the 9 others: it recurs.
    std::vector<DepthFrame> f = frames(12, {800, 802, 801});
    for (std::size_t i = 3; i < f.size(); ++i) f[i].depth_mm(kTip) = 0;
    EXPECT_EQ(recurringReadings(f).depth_mm(kTip), 801);
}

// The image-wide sort against the plain per-pixel definition, on frames of random readings:
// clusters at a few depths, scattered ones and gaps, for 5, 12 and 17 frames.
TEST(RecurringReadings, MatchesThePerPixelDefinition) {
    cv::RNG rng(7);
    for (const int count : {5, 12, 17}) {
        std::vector<DepthFrame> f(static_cast<std::size_t>(count));
        for (auto& frame : f) {
            frame.depth_mm = cv::Mat1w(24, 32);
            for (auto& d : frame.depth_mm) {
                const int kind = rng.uniform(0, 4);
                d = kind == 0   ? 0
                    : kind == 1 ? static_cast<std::uint16_t>(rng.uniform(500, 2000))
                                : static_cast<std::uint16_t>(700 * kind + rng.uniform(-8, 9));
            }
        }
        const RecurringParams params;
        const RecurringReadings r = recurringReadings(f, params);
        const auto needed = static_cast<std::size_t>(r.neededFrames);
        int recurring = 0;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 32; ++x) {
                std::vector<std::uint16_t> v;
                for (const auto& frame : f)
                    if (frame.depth_mm(y, x) != 0) v.push_back(frame.depth_mm(y, x));
                std::sort(v.begin(), v.end());
                std::uint16_t expected = 0;
                for (std::size_t i = 0; i + needed <= v.size(); ++i)
                    if (v[i + needed - 1] - v[i] <= params.agreement_mm) {
                        expected = v[i + (needed - 1) / 2];
                        break;
                    }
                recurring += expected != 0;
                ASSERT_EQ(r.depth_mm(y, x), expected)
                    << count << " frames, pixel " << x << ", " << y;
            }
        EXPECT_EQ(r.recurringPixels, recurring);
        EXPECT_GT(recurring, 0);
    }
}

TEST(RecurringReadings, BadInputIsOneClearError) {
    EXPECT_THROW((void)recurringReadings({}), CaptureError);
    std::vector<DepthFrame> f = frames(4, {});
    f[2].depth_mm = cv::Mat1w(9, 10, kWall_mm);
    try {
        (void)recurringReadings(f);
        FAIL() << "no error for frames of two sizes";
    } catch (const CaptureError& e) {
        EXPECT_NE(std::string(e.what()).find("frame 2 differs in size"), std::string::npos)
            << e.what();
    }
    RecurringParams params;
    params.minShare = 1.5f;
    EXPECT_THROW((void)recurringReadings(frames(4, {}), params), CaptureError);
    params = {};
    params.minFrames = 0;
    EXPECT_FALSE(params.problem().empty());
    params = {};
    params.agreement_mm = -1;
    EXPECT_FALSE(params.problem().empty());
}

}  // namespace
}  // namespace meadow::capture
