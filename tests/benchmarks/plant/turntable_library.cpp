#include "plant/turntable_library.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <iterator>
#include <map>
#include <opencv2/core.hpp>
#include <set>
#include <sstream>

#include "common/report.h"
#include "meadow/capture/depth_source.h"

namespace meadow::bench {
namespace {

HeldLeaves heldLeaves(const modeling::ArchetypeLibrary& library,
                      const synth::ScoringTruth& scoring) {
    HeldLeaves h;
    h.archetypes = static_cast<int>(library.archetypes.size());
    if (library.archetypes.empty()) return h;
    const synth::LibraryScore s = synth::scoreLibrary(library, scoring);
    std::map<int, std::vector<float>> errorsOf;  // per matched leaf, its archetypes' errors
    std::set<int> counted;
    for (const synth::ViewScore& v : s.views) {
        for (std::size_t m = 0; m < v.matchedIds.size(); ++m)
            errorsOf[v.matchedIds[m]].push_back(v.lengthError[m]);
        counted.insert(v.countedIds.begin(), v.countedIds.end());
        h.falseBlades += v.falseCount();
    }
    // Of the leaves counted in some view (a leaf matched only where it shows few pixels too).
    for (const auto& [id, errors] : errorsOf) {
        h.matching += static_cast<int>(errors.size());
        if (!counted.contains(id)) continue;
        ++h.held;
        h.lengthError.push_back(static_cast<float>(median(errors)));
    }
    h.counted = static_cast<int>(counted.size());
    return h;
}

// The angle of a rotation (degrees).
float rotationAngle_deg(const glm::mat3& r) {
    const float c = std::clamp((r[0][0] + r[1][1] + r[2][2] - 1.f) / 2.f, -1.f, 1.f);
    return glm::degrees(std::acos(c));
}

std::string cellOf(const HeldLeaves& h) {
    return std::to_string(h.archetypes) + " | " + std::to_string(h.held) + " | " +
           std::to_string(h.matching - h.held) + " | " + std::to_string(h.falseBlades) + " | " +
           (h.lengthError.empty() ? "-" : fixed(100.0 * median(h.lengthError), 0) + " %");
}

// The plant's own readings in each view (the truth's leaf and stem labels), by frame: the cloud
// capture registers (capture::plantCloud), with the truth's plant as the mask and no band.
std::map<int, capture::ViewCloud> truthPlantClouds(const std::filesystem::path& recording,
                                                   const synth::ScoringTruth& scoring) {
    std::map<int, const synth::TruthView*> truthView;
    for (const synth::TruthView& v : scoring.views) truthView[v.frame] = &v;
    std::map<int, capture::ViewCloud> clouds;
    auto source = capture::openDepthSource(recording.string());
    while (std::optional<capture::DepthFrame> frame = source->next()) {
        const auto found = truthView.find(frame->index);
        if (found == truthView.end()) continue;
        const synth::TruthView& view = *found->second;
        capture::Segmentation plant;
        plant.clusterMask = cv::Mat1b::zeros(frame->depth_mm.size());
        const auto add = [&](int label) {
            cv::bitwise_or(plant.clusterMask, view.labels == label, plant.clusterMask);
        };
        for (const synth::TruthLeaf& leaf : view.leaves) add(leaf.id);
        if (view.stemId != 0) add(view.stemId);
        clouds[frame->index] = capture::plantCloud(plant, *frame);
    }
    return clouds;
}

}  // namespace

void HeldLeaves::add(const HeldLeaves& o) {
    archetypes += o.archetypes, held += o.held, falseBlades += o.falseBlades;
    matching += o.matching, counted += o.counted;
    append(lengthError, o.lengthError);
}

void TurntableRow::add(const TurntableRow& o) {
    pairs += o.pairs, registered += o.registered, registrable += o.registrable;
    leaves += o.leaves;
    append(turnError_deg, o.turnError_deg);
    append(offset_mm, o.offset_mm);
    eachView.add(o.eachView);
    joined.add(o.joined);
    append(eachView_ms, o.eachView_ms);
    append(turntable_ms, o.turntable_ms);
}

TurntableRow scoreTurntable(const modeling::ArchetypeLibrary& eachView,
                            const modeling::CaptureResult& turntable,
                            const synth::PlantTruth& truth, const synth::ScoringTruth& scoring,
                            const std::filesystem::path& recording,
                            const capture::ViewRegistrationParams& registration) {
    TurntableRow row;
    std::map<int, glm::mat4> cameraFromWorld;
    for (const synth::PlantTruthView& v : truth.views) cameraFromWorld[v.index] = v.cameraFromWorld;
    std::map<int, const synth::TruthView*> truthView;
    for (const synth::TruthView& v : scoring.views) truthView[v.frame] = &v;

    // The recording's pairs, each view and the one before, whether capture found the plant in
    // them or not.
    const std::map<int, capture::ViewCloud> plantClouds = truthPlantClouds(recording, scoring);
    for (auto at = plantClouds.begin(); at != plantClouds.end(); ++at) {
        if (at == plantClouds.begin()) continue;
        const auto before = std::prev(at);
        ++row.pairs;
        const glm::mat4 trueMotion =
            cameraFromWorld.at(before->first) * glm::inverse(cameraFromWorld.at(at->first));
        if (capture::shareLyingOn(at->second, before->second, trueMotion, registration) >=
            registration.minInlierShare)
            ++row.registrable;
    }

    const std::vector<capture::RegisteredView>& views = turntable.turningViews;
    std::map<int, int> chainFirst;  // chain -> its first view's frame
    for (std::size_t i = 0; i < views.size(); ++i) {
        const capture::RegisteredView& v = views[i];
        chainFirst.emplace(v.chain, v.frame);
        if (i == 0 || !v.why.empty()) continue;
        ++row.registered;
        const glm::mat4 trueChainFromView =
            cameraFromWorld.at(chainFirst.at(v.chain)) * glm::inverse(cameraFromWorld.at(v.frame));
        row.turnError_deg.push_back(
            rotationAngle_deg(glm::mat3(glm::inverse(v.chainFromView) * trueChainFromView)));
        double sum = 0.0;
        int n = 0;
        if (const auto it = truthView.find(v.frame); it != truthView.end())
            for (const synth::TruthLeaf& leaf : it->second->leaves)
                for (const glm::vec3& p : leaf.line) {
                    sum += glm::distance(glm::vec3(v.chainFromView * glm::vec4(p, 1.f)),
                                         glm::vec3(trueChainFromView * glm::vec4(p, 1.f)));
                    ++n;
                }
        if (n > 0) row.offset_mm.push_back(static_cast<float>(1000.0 * sum / n));
    }
    row.eachView = heldLeaves(eachView, scoring);
    row.joined = heldLeaves(turntable.library, scoring);
    row.leaves = row.eachView.counted;
    return row;
}

std::string turntableSection(const std::vector<TurntableRow>& rows) {
    std::ostringstream md;
    md << "\n## A turntable as one library\n\n"
          "`meadow capture --turntable` on the same views (clusters + stem-graph): each view "
          "segmented alone, registered to the one before it (docs/capture.md, \"Turntable "
          "views\"), the archetypes of a leaf that another view shows longer left out, and those "
          "no other view shows; beside it the library of the views captured each alone, as "
          "above. Views registered: of the views after the "
          "first, those whose plant came to lie on the view before it (the rest start a chain of "
          "their own); registrable: those whose plant's own readings (the truth's leaf and stem "
          "pixels) lie on the view before's, at the true turn, as registration asks (60 % within "
          "10 mm): what the sensor's readings allow, whatever capture finds. Turn error: the angle "
          "between the registered and the true turn from the "
          "chain's first view (median); offset: how far the registration puts the view's true "
          "leaf points from where the truth puts them (median of the views' means). Leaves: "
          "those shown by 300 pixels in some view; held: of them, those an archetype matches; "
          "more: archetypes matching a leaf beyond one per leaf; false: archetypes matching no "
          "leaf; length error: per held leaf the median over its matching archetypes, median "
          "over the leaves. Time per view: the capture's total over its views, the views "
          "captured each alone and then as a turntable (median over the views; one core). The "
          "rows are also in plant_turntable.csv.\n\n"
          "| Sensor | Plant | Views registered (registrable) | Turn error (median) | Offset "
          "(median) | Leaves "
          "| Each view: archetypes | held | more | false | length error | Turntable: archetypes | "
          "held | more | false | length error | Time per view: each view | turntable |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const TurntableRow& r : rows)
        md << "| " << r.sensor << " | " << (r.plant == "all" ? "**all**" : r.plant) << " | "
           << r.registered << " of " << r.pairs << " (" << r.registrable << ") | "
           << (r.turnError_deg.empty() ? "-" : fixed(median(r.turnError_deg), 1) + " deg") << " | "
           << (r.offset_mm.empty() ? "-" : fixed(median(r.offset_mm), 0) + " mm") << " | "
           << r.leaves << " | " << cellOf(r.eachView) << " | " << cellOf(r.joined) << " | "
           << (r.eachView_ms.empty() ? "-" : fixed(median(r.eachView_ms), 0) + " ms") << " | "
           << (r.turntable_ms.empty() ? "-" : fixed(median(r.turntable_ms), 0) + " ms") << " |\n";
    return md.str();
}

std::string turntableCsv(const std::vector<TurntableRow>& rows) {
    std::ostringstream csv;
    csv << "sensor,plant,pairs,registered,registrable,turn_error_deg_median,offset_mm_median,"
           "leaves";
    for (const char* library : {"each_view", "turntable"})
        csv << ',' << library << "_archetypes," << library << "_held," << library << "_more,"
            << library << "_false," << library << "_length_error_median";
    csv << ",each_view_ms_median,turntable_ms_median\n";
    for (const TurntableRow& r : rows) {
        csv << r.sensor << ',' << r.plant << ',' << r.pairs << ',' << r.registered << ','
            << r.registrable << ',' << orBlank(r.turnError_deg, median(r.turnError_deg), 2) << ','
            << orBlank(r.offset_mm, median(r.offset_mm), 1) << ',' << r.leaves;
        for (const HeldLeaves* h : {&r.eachView, &r.joined})
            csv << ',' << h->archetypes << ',' << h->held << ',' << h->matching - h->held << ','
                << h->falseBlades << ',' << orBlank(h->lengthError, median(h->lengthError), 3);
        csv << ',' << orBlank(r.eachView_ms, median(r.eachView_ms), 1) << ','
            << orBlank(r.turntable_ms, median(r.turntable_ms), 1) << '\n';
    }
    return csv.str();
}

}  // namespace meadow::bench
