// fitTracks keeps blades, not pieces of leaves: an archetype shorter along its spine than
// CaptureOptions::minLengthToWidth times its widest width is skipped and said why, or, with
// keepFlagged, kept with that reason among its flags. Length is measured in metres, so a blade
// pointing at the camera, short in the image, is kept.
#include <gtest/gtest.h>

#include "meadow/modeling/blade_observations.h"
#include "meadow/modeling/capture_pipeline.h"

namespace meadow::modeling {
namespace {

// A straight blade of constant width from `base` along `direction` (camera space, metres).
Skeleton straightSkeleton(glm::vec3 base, glm::vec3 direction, float length_m, float width_m) {
    Skeleton s;
    constexpr int kSteps = 40;
    for (int i = 0; i <= kSteps; ++i) {
        const float t = static_cast<float>(i) / kSteps;
        s.points_m.push_back(base + length_m * t * glm::normalize(direction));
        s.width_m.push_back(width_m);
    }
    return s;
}

constexpr glm::vec3 kUpTheImage{0.f, -1.f, 0.f};

// Blade 1: 120 x 10 mm up the image; blade 2: a piece 30 mm long and 40 mm wide; blade 3:
// 120 x 10 mm leaning toward the camera (20 mm up the image, the rest in depth).
BladeObservations threeViews() {
    BladeObservations seen;
    const auto add = [&](int id, Skeleton skeleton) {
        seen.skeletons.push_back({0, std::move(skeleton)});
        BladeView view;
        view.sighting = {0, id};
        seen.views.push_back(std::move(view));
    };
    add(1, straightSkeleton({0.f, 0.1f, 0.6f}, kUpTheImage, 0.12f, 0.01f));
    add(2, straightSkeleton({0.1f, 0.1f, 0.6f}, kUpTheImage, 0.03f, 0.04f));
    add(3, straightSkeleton({-0.1f, 0.1f, 0.7f}, {0.f, -0.02f, -0.118f}, 0.12f, 0.01f));
    return seen;
}

const std::vector<std::vector<std::size_t>> kOneTrackEach{{0}, {1}, {2}};

float lengthToWidth(const Archetype& a) { return a.height_m() / a.width.maxWidth_m(); }

std::vector<int> bladeIds(const std::vector<TrackFit>& fits) {
    std::vector<int> ids;
    for (const TrackFit& f : fits) ids.push_back(f.fit.archetype.source.bladeId);
    return ids;
}

TEST(FitTracks, APieceShorterThanTwiceItsWidthIsSkippedAndSaysWhy) {
    CaptureSummary summary;
    const std::vector<TrackFit> fits =
        fitTracks(threeViews(), kOneTrackEach, CaptureOptions{}, "made", summary);
    EXPECT_EQ(bladeIds(fits), (std::vector<int>{1, 3}));
    for (const TrackFit& f : fits) {
        EXPECT_GT(lengthToWidth(f.fit.archetype), 10.f);
        EXPECT_TRUE(f.fit.archetype.source.flags.empty());
    }
    ASSERT_TRUE(summary.skippedBy.contains(kTooShortForItsWidth));
    EXPECT_EQ(summary.skippedBy.at(kTooShortForItsWidth), 1);
    ASSERT_EQ(summary.notes.size(), 1u);
    EXPECT_TRUE(summary.notes[0].starts_with("frame 0 blade 2 skipped: too-short-for-its-width: "))
        << summary.notes[0];
    EXPECT_NE(summary.notes[0].find("mm long and 4"), std::string::npos) << summary.notes[0];
    EXPECT_NE(skippedSummary(summary).find("too-short-for-its-width (1)"), std::string::npos);
}

TEST(FitTracks, KeepFlaggedKeepsThePieceAndListsWhy) {
    CaptureOptions options;
    options.keepFlagged = true;
    CaptureSummary summary;
    const std::vector<TrackFit> fits =
        fitTracks(threeViews(), kOneTrackEach, options, "made", summary);
    ASSERT_EQ(bladeIds(fits), (std::vector<int>{1, 2, 3}));
    const Archetype& piece = fits[1].fit.archetype;
    EXPECT_LT(lengthToWidth(piece), 2.f);
    ASSERT_EQ(piece.source.flags.size(), 1u);
    EXPECT_TRUE(piece.source.flags[0].starts_with("too-short-for-its-width: "));
    EXPECT_TRUE(fits[0].fit.archetype.source.flags.empty());
    EXPECT_TRUE(summary.skippedBy.empty());
}

TEST(FitTracks, ARatioOfZeroKeepsEveryShape) {
    CaptureOptions options;
    options.minLengthToWidth = 0.f;
    CaptureSummary summary;
    const std::vector<TrackFit> fits =
        fitTracks(threeViews(), kOneTrackEach, options, "made", summary);
    EXPECT_EQ(bladeIds(fits), (std::vector<int>{1, 2, 3}));
    for (const TrackFit& f : fits) EXPECT_TRUE(f.fit.archetype.source.flags.empty());
    EXPECT_TRUE(summary.notes.empty());
}

}  // namespace
}  // namespace meadow::modeling
