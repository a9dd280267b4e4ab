#include "meadow/synth/library_score.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "meadow/core/json_reader.h"
#include "meadow/synth/error.h"
#include "meadow/synth/plant_synthesize.h"

namespace meadow::synth {
namespace {

// Points each curve is sampled at, evenly by arc length.
constexpr int kSamples = 50;

std::vector<glm::vec3> resample(const std::vector<glm::vec3>& line, int n) {
    std::vector<float> cumulative(line.size(), 0.f);
    for (std::size_t i = 1; i < line.size(); ++i)
        cumulative[i] = cumulative[i - 1] + glm::distance(line[i - 1], line[i]);
    std::vector<glm::vec3> out;
    if (line.size() < 2)
        return std::vector<glm::vec3>(static_cast<std::size_t>(n),
                                      line.empty() ? glm::vec3(0.f) : line.front());
    std::size_t seg = 0;
    for (int k = 0; k < n; ++k) {
        const float target = cumulative.back() * static_cast<float>(k) / static_cast<float>(n - 1);
        while (seg + 2 < line.size() && cumulative[seg + 1] < target) ++seg;
        const float len = cumulative[seg + 1] - cumulative[seg];
        const float f = len > 0.f ? std::clamp((target - cumulative[seg]) / len, 0.f, 1.f) : 0.f;
        out.push_back(glm::mix(line[seg], line[seg + 1], f));
    }
    return out;
}

float distanceToPolyline(glm::vec3 p, const std::vector<glm::vec3>& line) {
    float best = std::numeric_limits<float>::max();
    for (std::size_t i = 1; i < line.size(); ++i) {
        const glm::vec3 a = line[i - 1], ab = line[i] - a;
        const float l2 = glm::dot(ab, ab);
        const float t = l2 > 0.f ? std::clamp(glm::dot(p - a, ab) / l2, 0.f, 1.f) : 0.f;
        best = std::min(best, glm::distance(p, a + t * ab));
    }
    return line.size() == 1 ? glm::distance(p, line.front()) : best;
}

// The share of `line`'s length from its start to its point nearest `p`.
float arcShareNearest(glm::vec3 p, const std::vector<glm::vec3>& line) {
    if (line.size() < 2) return 0.f;
    float best = std::numeric_limits<float>::max(), along = 0.f, bestAlong = 0.f;
    for (std::size_t i = 1; i < line.size(); ++i) {
        const glm::vec3 a = line[i - 1], ab = line[i] - a;
        const float l2 = glm::dot(ab, ab), l = std::sqrt(l2);
        const float t = l2 > 0.f ? std::clamp(glm::dot(p - a, ab) / l2, 0.f, 1.f) : 0.f;
        if (const float d = glm::distance(p, a + t * ab); d < best)
            best = d, bestAlong = along + t * l;
        along += l;
    }
    return along > 0.f ? bestAlong / along : 0.f;
}

float polylineLength(const std::vector<glm::vec3>& line) {
    float l = 0.f;
    for (std::size_t i = 1; i < line.size(); ++i) l += glm::distance(line[i - 1], line[i]);
    return l;
}

// Share of the shorter curve's samples within the tolerance of the other curve.
float coverage(const std::vector<glm::vec3>& spine, const TruthLeaf& leaf, const MatchRule& rule) {
    const float tolerance = std::max(rule.minTolerance_m, rule.lengthShare * leaf.length_m);
    const bool spineShorter = polylineLength(spine) <= polylineLength(leaf.line);
    const std::vector<glm::vec3> shorter = resample(spineShorter ? spine : leaf.line, kSamples);
    const std::vector<glm::vec3>& other = spineShorter ? leaf.line : spine;
    int within = 0;
    for (const glm::vec3& p : shorter) within += distanceToPolyline(p, other) <= tolerance;
    return static_cast<float>(within) / static_cast<float>(kSamples);
}

FalseBladeOn classify(std::uint16_t label, const TruthView& view) {
    if (label == 0) return FalseBladeOn::Nothing;
    if (view.stemId != 0 && label == view.stemId) return FalseBladeOn::Stem;
    switch (label) {
        case kPotLabel:
            return FalseBladeOn::Pot;
        case kFloorLabel:
            return FalseBladeOn::Floor;
        case kWallLabel:
            return FalseBladeOn::Wall;
        case kClutterLabel:
            return FalseBladeOn::Clutter;
        default:
            return FalseBladeOn::Leaf;
    }
}

// What most of the spine lies on in the view's labels.
FalseBladeOn underSpine(const std::vector<glm::vec3>& spine, const TruthView& view,
                        const capture::Intrinsics& k) {
    std::array<int, 7> votes{};
    for (const glm::vec3& p : spine) {
        if (!(p.z > 0.f)) continue;
        const glm::vec2 px = k.project(p);
        const int u = static_cast<int>(std::lround(px.x)), v = static_cast<int>(std::lround(px.y));
        if (u < 0 || v < 0 || u >= view.labels.cols || v >= view.labels.rows) continue;
        ++votes[static_cast<std::size_t>(classify(view.labels(v, u), view))];
    }
    return static_cast<FalseBladeOn>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

cv::Mat1w readLabels(const std::filesystem::path& file) {
    const cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
    if (image.empty() || image.type() != CV_16UC1)
        throw SynthError(file.string() + ": not a readable 16-bit label image");
    return image;
}

double median(std::vector<float> v) {
    if (v.empty()) return std::nan("");
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

std::vector<glm::vec3> spineInCamera(const modeling::Archetype& a) {
    std::vector<glm::vec3> out;
    for (int k = 0; k < kSamples; ++k) {
        const float t = a.spine_m.parameterAtLengthFraction(static_cast<float>(k) / (kSamples - 1));
        out.push_back(glm::vec3(a.source.cameraFromBlade * glm::vec4(a.spine_m.at(t), 1.f)));
    }
    return out;
}

ScoringTruth scoringTruthOf(const PlantTruth& truth, const std::filesystem::path& truthFolder) {
    ScoringTruth out;
    out.what = "plant " + truth.plant;
    out.intrinsics = truth.intrinsics;
    for (const PlantTruthView& v : truth.views) {
        TruthView view;
        view.frame = v.index;
        view.labels = readLabels(truthFolder / v.labels);
        for (const PlantTruthOrgan& o : v.organs) {
            if (o.stem) {
                view.stemId = o.id;
                continue;
            }
            view.leaves.push_back(
                {o.id, o.centreLineCamera_m, o.length_m, o.maxWidth_m, o.visiblePixels});
        }
        out.views.push_back(std::move(view));
    }
    return out;
}

ScoringTruth scoringTruthOf(const SynthTruth& truth, const std::filesystem::path& truthFolder) {
    ScoringTruth out;
    out.what = "preset " + truth.preset;
    out.intrinsics = truth.intrinsics;
    for (const SynthTruthFrame& f : truth.frames) {
        TruthView view;
        view.frame = f.index;
        view.labels = readLabels(truthFolder / f.labels);
        for (const SynthTruthBlade& b : f.blades) {
            TruthLeaf leaf;
            leaf.id = b.id;
            for (int k = 0; k < kSamples; ++k)
                leaf.line.push_back(b.spineCamera_m.at(b.spineCamera_m.parameterAtLengthFraction(
                    static_cast<float>(k) / (kSamples - 1))));
            leaf.length_m = b.height_m;
            leaf.maxWidth_m = *std::max_element(b.width_m.begin(), b.width_m.end());
            leaf.visiblePixels = cv::countNonZero(view.labels == b.id);
            view.leaves.push_back(std::move(leaf));
        }
        out.views.push_back(std::move(view));
    }
    return out;
}

ScoringTruth readScoringTruth(const std::filesystem::path& file) {
    const std::filesystem::path folder = file.parent_path();
    if (file.filename() == "plant.json") return scoringTruthOf(readPlantTruth(file), folder);
    return scoringTruthOf(readSynthTruth(file), folder);
}

int ViewScore::falseCount() const {
    int n = 0;
    for (int c : falseBlades) n += c;
    return n;
}

int LibraryScore::leaves() const {
    int n = 0;
    for (const ViewScore& v : views) n += v.leaves;
    return n;
}
int LibraryScore::matched() const {
    int n = 0;
    for (const ViewScore& v : views) n += v.matched;
    return n;
}
double LibraryScore::recall() const {
    return leaves() > 0 ? static_cast<double>(matched()) / leaves() : 0.0;
}
double LibraryScore::falsePerView() const {
    double n = 0;
    for (const ViewScore& v : views) n += v.falseCount();
    return views.empty() ? 0.0 : n / static_cast<double>(views.size());
}
double LibraryScore::falsePerView(FalseBladeOn on) const {
    double n = 0;
    for (const ViewScore& v : views) n += v.falseBlades[static_cast<std::size_t>(on)];
    return views.empty() ? 0.0 : n / static_cast<double>(views.size());
}
double LibraryScore::medianOver(std::vector<float> ViewScore::*perMatch) const {
    std::vector<float> all;
    for (const ViewScore& v : views)
        all.insert(all.end(), (v.*perMatch).begin(), (v.*perMatch).end());
    return median(std::move(all));
}
double LibraryScore::medianLengthError() const { return medianOver(&ViewScore::lengthError); }
double LibraryScore::medianWidthError() const { return medianOver(&ViewScore::widthError); }
double LibraryScore::medianBaseMissed() const { return medianOver(&ViewScore::baseMissed); }
double LibraryScore::medianTipMissed() const { return medianOver(&ViewScore::tipMissed); }
double LibraryScore::upsideDownShare() const {
    double sum = 0.0;
    std::size_t n = 0;
    for (const ViewScore& v : views) {
        for (const float u : v.upsideDown) sum += u;
        n += v.upsideDown.size();
    }
    return n ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}
AnyViewScore LibraryScore::anyView() const {
    std::set<int> counted;
    std::map<int, float> best;  // smallest length error per leaf matched in some view
    for (const ViewScore& v : views) {
        counted.insert(v.countedIds.begin(), v.countedIds.end());
        for (std::size_t m = 0; m < v.matchedIds.size(); ++m) {
            const auto [at, added] = best.emplace(v.matchedIds[m], v.lengthError[m]);
            if (!added) at->second = std::min(at->second, v.lengthError[m]);
        }
    }
    AnyViewScore any;
    any.leaves = static_cast<int>(counted.size());
    for (const auto& [id, error] : best)
        if (counted.count(id)) {
            ++any.matched;
            any.bestLengthError.push_back(error);
        }
    return any;
}
double LibraryScore::meanCountError() const {
    double sum = 0;
    for (const ViewScore& v : views) sum += std::abs(v.archetypes - v.leaves);
    return views.empty() ? 0.0 : sum / static_cast<double>(views.size());
}

LibraryScore scoreLibrary(const modeling::ArchetypeLibrary& library, const ScoringTruth& truth,
                          const MatchRule& rule) {
    for (const modeling::Archetype& a : library.archetypes)
        if (!a.source.placed)
            throw SynthError(
                "archetype '" + a.name +
                "' does not say where it stood (no source.camera_from_blade_row_major): "
                "capture it again with this meadow to score it");
    LibraryScore score;
    score.what = truth.what;
    for (const TruthView& view : truth.views) {
        ViewScore vs;
        vs.frame = view.frame;
        std::vector<const modeling::Archetype*> mine;
        for (const modeling::Archetype& a : library.archetypes)
            if (a.source.frame == view.frame) mine.push_back(&a);
        vs.archetypes = static_cast<int>(mine.size());
        std::vector<std::vector<glm::vec3>> spines;
        for (const modeling::Archetype* a : mine) spines.push_back(spineInCamera(*a));
        // Every pair that passes, best coverage first, one to one.
        struct Pair {
            float coverage;
            std::size_t archetype, leaf;
        };
        std::vector<Pair> pairs;
        for (std::size_t a = 0; a < mine.size(); ++a)
            for (std::size_t l = 0; l < view.leaves.size(); ++l)
                if (const float c = coverage(spines[a], view.leaves[l], rule); c >= rule.coverage)
                    pairs.push_back({c, a, l});
        std::stable_sort(pairs.begin(), pairs.end(),
                         [](const Pair& x, const Pair& y) { return x.coverage > y.coverage; });
        std::vector<char> archetypeUsed(mine.size(), 0), leafUsed(view.leaves.size(), 0);
        for (const Pair& p : pairs) {
            if (archetypeUsed[p.archetype] || leafUsed[p.leaf]) continue;
            archetypeUsed[p.archetype] = leafUsed[p.leaf] = 1;
            const TruthLeaf& leaf = view.leaves[p.leaf];
            const modeling::Archetype& a = *mine[p.archetype];
            vs.lengthError.push_back(std::abs(a.height_m() - leaf.length_m) / leaf.length_m);
            vs.matchedIds.push_back(leaf.id);
            if (leaf.maxWidth_m > 0.f)
                vs.widthError.push_back(std::abs(a.width.maxWidth_m() - leaf.maxWidth_m) /
                                        leaf.maxWidth_m);
            const std::vector<glm::vec3>& spine = spines[p.archetype];
            const float one = arcShareNearest(spine.front(), leaf.line);
            const float other = arcShareNearest(spine.back(), leaf.line);
            vs.baseMissed.push_back(std::min(one, other));
            vs.tipMissed.push_back(1.f - std::max(one, other));
            if (std::abs(other - one) >= kOrientedSpan) vs.upsideDown.push_back(one > other);
        }
        for (std::size_t l = 0; l < view.leaves.size(); ++l)
            if (view.leaves[l].visiblePixels >= rule.minVisiblePixels) {
                ++vs.leaves;
                vs.matched += leafUsed[l];
                vs.countedIds.push_back(view.leaves[l].id);
            }
        for (std::size_t a = 0; a < mine.size(); ++a)
            if (!archetypeUsed[a])
                ++vs.falseBlades[static_cast<std::size_t>(
                    underSpine(spines[a], view, truth.intrinsics))];
        score.views.push_back(std::move(vs));
    }
    return score;
}

}  // namespace meadow::synth
