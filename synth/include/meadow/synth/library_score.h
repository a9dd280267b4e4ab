#pragma once
// Scores a capture's archetype library against the truth of what it captured: a scanned plant on
// the bench (plant_synthesize.h) or a synthetic tuft (synthesize.h). Each archetype is placed in
// its view's camera space (Source::cameraFromBlade, Source::frame) and matched to the true leaves
// of that view:
//
//   an archetype matches a leaf when its spine stays within max(10 mm, 5 % of the leaf's
//   length) of the leaf's true centre line over at least 80 % of the shorter of the two;
//
// one archetype to one leaf, best coverage first. Where a matched archetype's ends fall on the
// leaf's centre line (each end's nearest point) tells where it comes out short: the share of the
// leaf below its lower end (missed at the base) and beyond its upper end (missed at the tip).
// Leaves with at least 300 visible pixels count
// for recall. An archetype that matches no leaf is a false blade, named by what most of its spine
// lies on in the view's label image (the stem, the pot, the floor, the wall, clutter, another
// blade or leaf, or nothing).
#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/core/enum_names.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/synth/plant_views.h"
#include "meadow/synth/synthesize.h"

namespace meadow::synth {

struct TruthLeaf {
    int id = 0;                   // its label value
    std::vector<glm::vec3> line;  // camera space, base to tip
    float length_m = 0.f;
    float maxWidth_m = 0.f;
    int visiblePixels = 0;
};

struct TruthView {
    int frame = 0;     // the recording's frame it was seen in
    cv::Mat1w labels;  // label image
    std::vector<TruthLeaf> leaves;
    int stemId = 0;  // the stem's label value (0: none)
};

struct ScoringTruth {
    std::string what;  // "plant v-9-1-l-r", "preset quadratic-leaf"
    capture::Intrinsics intrinsics;
    std::vector<TruthView> views;
};

// From a plant's truth (the stem is not a leaf) and a tuft's (every blade is one); label images
// read from `truthFolder`. Throws SynthError naming a label image that cannot be read.
[[nodiscard]] ScoringTruth scoringTruthOf(const PlantTruth& truth,
                                          const std::filesystem::path& truthFolder);
[[nodiscard]] ScoringTruth scoringTruthOf(const SynthTruth& truth,
                                          const std::filesystem::path& truthFolder);
// Reads truth/plant.json or truth/blades.json, whichever `file` is.
[[nodiscard]] ScoringTruth readScoringTruth(const std::filesystem::path& file);

enum class FalseBladeOn { Stem, Pot, Floor, Wall, Clutter, Leaf, Nothing };
inline constexpr EnumNames<FalseBladeOn, 7> kFalseBladeOnNames{{{
    {FalseBladeOn::Stem, "stem"},
    {FalseBladeOn::Pot, "pot"},
    {FalseBladeOn::Floor, "floor"},
    {FalseBladeOn::Wall, "wall"},
    {FalseBladeOn::Clutter, "clutter"},
    {FalseBladeOn::Leaf, "leaf"},
    {FalseBladeOn::Nothing, "nothing"},
}}};

struct MatchRule {
    float minTolerance_m = 0.01f;
    float lengthShare = 0.05f;   // of the true leaf's length
    float coverage = 0.8f;       // of the shorter one
    int minVisiblePixels = 300;  // for a leaf to count in recall
};

// An archetype's way along its leaf is read only where its ends lie this far apart along the
// leaf (a share of its length): a short piece's ends fall within the readings' scatter.
inline constexpr float kOrientedSpan = 0.2f;

struct ViewScore {
    int frame = 0;
    int leaves = 0;                    // true leaves with at least minVisiblePixels
    int matched = 0;                   // of them, matched
    int archetypes = 0;                // the library's archetypes from this view
    std::array<int, 7> falseBlades{};  // by FalseBladeOn
    std::vector<float> lengthError;    // |archetype - leaf| / leaf, per matched leaf
    std::vector<float> widthError;     // |widest archetype - widest leaf| / widest leaf
    std::vector<float> baseMissed;     // share of the matched leaf's line below the archetype
    std::vector<float> tipMissed;      // share of it beyond the archetype's upper end
    // Per matched leaf whose archetype spans at least kOrientedSpan of it: 1 when the archetype
    // runs from the leaf's tip side toward its base (it would be planted by its tip), else 0.
    std::vector<float> upsideDown;
    std::vector<int> matchedIds;  // the matched leaves' label values, in lengthError's order
    std::vector<int> countedIds;  // those of the leaves counted in `leaves`
    [[nodiscard]] int falseCount() const;
};

// What a library over all views holds of the plant: a leaf that overlaps others in one view may
// stand clear in another, and a library needs each leaf once. Leaves are told apart by their
// label value, the same in every view of one plant or tuft.
struct AnyViewScore {
    int leaves = 0;                      // leaves counted (minVisiblePixels) in at least one view
    int matched = 0;                     // of them, matched in at least one view
    std::vector<float> bestLengthError;  // per leaf matched anywhere: its smallest length error
};

struct LibraryScore {
    std::string what;
    std::vector<ViewScore> views;
    [[nodiscard]] int leaves() const;
    [[nodiscard]] int matched() const;
    [[nodiscard]] double recall() const;  // matched / leaves (0 without leaves)
    [[nodiscard]] double falsePerView() const;
    [[nodiscard]] double falsePerView(FalseBladeOn on) const;
    [[nodiscard]] double medianLengthError() const;  // NaN without matches
    [[nodiscard]] double medianWidthError() const;
    [[nodiscard]] double medianBaseMissed() const;  // NaN without matches
    [[nodiscard]] double medianTipMissed() const;
    [[nodiscard]] double meanCountError() const;   // |archetypes in a view - leaves| per view
    [[nodiscard]] double upsideDownShare() const;  // of ViewScore::upsideDown; NaN without any
    [[nodiscard]] AnyViewScore anyView() const;

private:
    // The median of one per-match list over every view (NaN when empty).
    [[nodiscard]] double medianOver(std::vector<float> ViewScore::*perMatch) const;
};

// The archetype's spine where it stood, in its view's camera space (metres): points evenly
// spaced along its length, base to tip, as scoring reads it. Needs a placed source.
[[nodiscard]] std::vector<glm::vec3> spineInCamera(const modeling::Archetype& a);

// Throws SynthError when an archetype carries no camera placement (a library from an older
// meadow, or authored).
[[nodiscard]] LibraryScore scoreLibrary(const modeling::ArchetypeLibrary& library,
                                        const ScoringTruth& truth, const MatchRule& rule = {});

}  // namespace meadow::synth
