// The scorer behind the plant benchmark's figures (library_score.h): which archetype matches
// which true leaf, what a false blade lies on, and where a matched archetype comes out short.
// One view of one straight leaf 40 cm long, 1 m before the camera, upright in the image.
#include "meadow/synth/library_score.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/vec3.hpp>
#include <opencv2/imgproc.hpp>

#include "meadow/synth/error.h"

namespace meadow::synth {
namespace {

constexpr int kLeafLabel = 5;
constexpr float kDepth_m = 1.f;
// The leaf runs up the image: camera y from +0.2 m (its base, below the centre) to -0.2 m.
constexpr float kBaseY_m = 0.2f, kTipY_m = -0.2f, kLength_m = kBaseY_m - kTipY_m;

ScoringTruth oneLeaf() {
    ScoringTruth truth;
    truth.what = "one upright leaf";
    TruthView view;
    view.frame = 0;
    view.labels = cv::Mat1w::zeros(truth.intrinsics.height_px, truth.intrinsics.width_px);
    const glm::vec2 base = truth.intrinsics.project({0.f, kBaseY_m, kDepth_m});
    const glm::vec2 tip = truth.intrinsics.project({0.f, kTipY_m, kDepth_m});
    cv::line(view.labels, cv::Point(cvRound(base.x), cvRound(base.y)),
             cv::Point(cvRound(tip.x), cvRound(tip.y)), kLeafLabel, 9);
    TruthLeaf leaf;
    leaf.id = kLeafLabel;
    for (int i = 0; i <= 20; ++i)
        leaf.line.push_back({0.f, kBaseY_m - kLength_m * static_cast<float>(i) / 20.f, kDepth_m});
    leaf.length_m = kLength_m;
    leaf.maxWidth_m = 0.02f;
    leaf.visiblePixels = cv::countNonZero(view.labels == kLeafLabel);
    view.leaves.push_back(leaf);
    truth.views.push_back(view);
    return truth;
}

// A straight archetype from camera point `from` to `to`, 2 cm wide, placed in frame 0.
modeling::Archetype straight(glm::vec3 from, glm::vec3 to) {
    modeling::Archetype a;
    a.name = "straight";
    a.spine_m = {glm::vec3(0.f), 0.5f * (to - from), to - from};
    a.width.width_m = {0.02f, 0.02f, 0.f};
    a.source.frame = 0;
    a.source.placed = true;
    a.source.cameraFromBlade = glm::mat4(1.f);
    a.source.cameraFromBlade[3] = glm::vec4(from, 1.f);
    return a;
}

modeling::ArchetypeLibrary libraryOf(std::vector<modeling::Archetype> archetypes) {
    modeling::ArchetypeLibrary library;
    library.archetypes = std::move(archetypes);
    return library;
}

TEST(LibraryScore, AnArchetypeAlongTheLeafsUpperPartMatchesItAndIsShortAtTheBase) {
    // From 40 % of the way up to the tip: 60 % of the leaf's length.
    const float from = kBaseY_m - 0.4f * kLength_m;
    const LibraryScore s = scoreLibrary(
        libraryOf({straight({0.f, from, kDepth_m}, {0.f, kTipY_m, kDepth_m})}), oneLeaf());
    ASSERT_EQ(s.views.size(), 1u);
    EXPECT_EQ(s.leaves(), 1);
    EXPECT_EQ(s.matched(), 1);
    EXPECT_DOUBLE_EQ(s.falsePerView(), 0.0);
    EXPECT_NEAR(s.medianLengthError(), 0.4, 1e-3);
    EXPECT_NEAR(s.medianBaseMissed(), 0.4, 1e-3);
    EXPECT_NEAR(s.medianTipMissed(), 0.0, 1e-3);
    EXPECT_NEAR(s.medianWidthError(), 0.0, 1e-3);
    EXPECT_DOUBLE_EQ(s.upsideDownShare(), 0.0) << "it runs from its base up, as the leaf does";
}

// The ends are read where they fall on the line, whichever way the spine runs: one drawn from
// the tip down, stopping short at both ends, misses 10 % at the base and 25 % at the tip; it runs
// upside down.
TEST(LibraryScore, WhereTheArchetypeStopsShortIsReadFromBothItsEnds) {
    const float lower = kBaseY_m - 0.1f * kLength_m, upper = kBaseY_m - 0.75f * kLength_m;
    const LibraryScore s = scoreLibrary(
        libraryOf({straight({0.f, upper, kDepth_m}, {0.f, lower, kDepth_m})}), oneLeaf());
    EXPECT_EQ(s.matched(), 1);
    EXPECT_NEAR(s.medianBaseMissed(), 0.1, 1e-3);
    EXPECT_NEAR(s.medianTipMissed(), 0.25, 1e-3);
    EXPECT_DOUBLE_EQ(s.upsideDownShare(), 1.0) << "its base end lies toward the leaf's tip";
}

// Whether an archetype runs the leaf's way is read only over a fifth of the leaf or more: a
// piece from 50 % down to 40 % (a tenth) tells nothing, and leaves the share unread.
TEST(LibraryScore, AShortPiecesWayAlongTheLeafIsNotRead) {
    const float lower = kBaseY_m - 0.4f * kLength_m, upper = kBaseY_m - 0.5f * kLength_m;
    const LibraryScore s = scoreLibrary(
        libraryOf({straight({0.f, upper, kDepth_m}, {0.f, lower, kDepth_m})}), oneLeaf());
    EXPECT_EQ(s.matched(), 1);
    EXPECT_TRUE(std::isnan(s.upsideDownShare()));
}

// 3 cm beside the leaf is beyond max(10 mm, 5 % of 40 cm = 20 mm): no match, and a false blade
// named by what lies under it (nothing: the label image holds the leaf alone).
TEST(LibraryScore, AnArchetypeBesideTheLeafIsAFalseBladeOnWhatLiesUnderIt) {
    const LibraryScore beside = scoreLibrary(
        libraryOf({straight({0.03f, kBaseY_m, kDepth_m}, {0.03f, kTipY_m, kDepth_m})}), oneLeaf());
    EXPECT_EQ(beside.matched(), 0);
    EXPECT_DOUBLE_EQ(beside.falsePerView(FalseBladeOn::Nothing), 1.0);
    EXPECT_TRUE(std::isnan(beside.medianBaseMissed()));
    // 1 cm beside it, within the tolerance: the same archetype matches.
    const LibraryScore near = scoreLibrary(
        libraryOf({straight({0.01f, kBaseY_m, kDepth_m}, {0.01f, kTipY_m, kDepth_m})}), oneLeaf());
    EXPECT_EQ(near.matched(), 1);
}

// Two pieces of one leaf: one matches it (the one covering more of the shorter curve, both
// lying wholly on it: the first), the other is a false blade on the leaf.
TEST(LibraryScore, TwoPiecesOfOneLeafAreOneMatchAndOneFalseBladeOnTheLeaf) {
    const float middle = kBaseY_m - 0.5f * kLength_m;
    const LibraryScore s =
        scoreLibrary(libraryOf({straight({0.f, kBaseY_m, kDepth_m}, {0.f, middle, kDepth_m}),
                                straight({0.f, middle, kDepth_m}, {0.f, kTipY_m, kDepth_m})}),
                     oneLeaf());
    EXPECT_EQ(s.matched(), 1);
    EXPECT_DOUBLE_EQ(s.falsePerView(FalseBladeOn::Leaf), 1.0);
    EXPECT_EQ(s.views[0].archetypes, 2);
    EXPECT_DOUBLE_EQ(s.meanCountError(), 1.0);
}

TEST(LibraryScore, AnArchetypeThatDoesNotSayWhereItStoodIsRefused) {
    modeling::Archetype authored = straight({0.f, kBaseY_m, kDepth_m}, {0.f, kTipY_m, kDepth_m});
    authored.source.placed = false;
    EXPECT_THROW((void)scoreLibrary(libraryOf({authored}), oneLeaf()), SynthError);
}

// A library over a turntable's views holds a leaf once it is matched in any of them, at its best
// view's length: the leaf in three views, matched from 40 % up in the first and from 10 % up in
// the second; a second leaf, shown only in the third view, is matched nowhere.
TEST(LibraryScore, AnyViewHoldsALeafMatchedInOneViewAtItsBestLength) {
    ScoringTruth truth = oneLeaf();
    for (int frame : {1, 2}) {
        TruthView view = truth.views.front();
        view.frame = frame;
        view.labels = view.labels.clone();
        truth.views.push_back(view);
    }
    TruthLeaf other = truth.views[2].leaves.front();
    other.id = kLeafLabel + 1;
    for (glm::vec3& p : other.line) p.x += 0.2f;  // 20 cm to the side
    truth.views[2].leaves.push_back(other);
    const auto from = [](float share, int frame) {
        modeling::Archetype a =
            straight({0.f, kBaseY_m - share * kLength_m, kDepth_m}, {0.f, kTipY_m, kDepth_m});
        a.source.frame = frame;
        return a;
    };
    const LibraryScore s = scoreLibrary(libraryOf({from(0.4f, 0), from(0.1f, 1)}), truth);
    EXPECT_EQ(s.leaves(), 4);
    EXPECT_EQ(s.matched(), 2);
    const AnyViewScore any = s.anyView();
    EXPECT_EQ(any.leaves, 2);
    EXPECT_EQ(any.matched, 1);
    ASSERT_EQ(any.bestLengthError.size(), 1u);
    EXPECT_NEAR(any.bestLengthError.front(), 0.1, 1e-3);
}

}  // namespace
}  // namespace meadow::synth
