#include "plant/truth_partition.h"

#include <algorithm>
#include <map>
#include <opencv2/imgproc.hpp>

#include "meadow/capture/blade_contour.h"
#include "meadow/capture/depth_source.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/error.h"

namespace meadow::bench {

namespace {

// Fewer read pixels than this hold no contour worth cutting.
constexpr int kMinLeafPixels = 30;

// The leaf's largest read piece as a blade: its contour from the point nearest its true base,
// round its true tip and back; and as a cluster of its own whose base point is that base.
bool addLeaf(const synth::TruthLeaf& leaf, const cv::Mat1b& pixels, const capture::Intrinsics& k,
             capture::Segmentation& seg) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(pixels, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty()) return false;
    const auto largest = std::max_element(
        contours.begin(), contours.end(),
        [](const auto& a, const auto& b) { return cv::contourArea(a) < cv::contourArea(b); });
    std::vector<cv::Point> contour = *largest;
    if (contour.size() < 8) return false;
    const glm::vec2 base = k.project(leaf.line.front());
    const glm::vec2 tip = k.project(leaf.line.back());
    const int from = capture::nearestPointIndex(contour, {base.x, base.y});
    std::rotate(contour.begin(), contour.begin() + from, contour.end());
    capture::BladeContour blade;
    blade.id = static_cast<int>(seg.blades.size()) + 1;
    blade.tipIndex = capture::nearestPointIndex(contour, {tip.x, tip.y});
    if (blade.tipIndex == 0) return false;
    const cv::Rect box = cv::boundingRect(contour);
    cv::Mat1b own = cv::Mat1b::zeros(pixels.size());
    cv::drawContours(own, std::vector<std::vector<cv::Point>>{contour}, 0, 255, cv::FILLED);
    blade.mask = own(box).clone();
    blade.maskOrigin_px = box.tl();
    blade.contour_px = contour;
    capture::BladeCluster cluster;
    cluster.contour_px = contour;
    cluster.basePoint_px = cluster.reference_px = cluster.centre_px = {base.x, base.y};
    cluster.bladeIds = {blade.id};
    cluster.area_px = cv::countNonZero(blade.mask);
    seg.clusterMask |= own;
    seg.blades.push_back(std::move(blade));
    seg.clusters.push_back(std::move(cluster));
    return true;
}

}  // namespace

modeling::ArchetypeLibrary modelTruthLeaves(const std::filesystem::path& recording,
                                            const synth::ScoringTruth& truth,
                                            const modeling::CaptureOptions& options,
                                            TruthBase base) {
    modeling::BladeFitParams fit = options.fit;
    if (base == TruthBase::LowestSeen) fit.root.enabled = false;
    std::map<int, const synth::TruthView*> views;
    for (const synth::TruthView& v : truth.views) views[v.frame] = &v;
    modeling::ArchetypeLibrary library;
    auto source = capture::openDepthSource(recording.string());
    while (std::optional<capture::DepthFrame> frame = source->next()) {
        const auto found = views.find(frame->index);
        if (found == views.end()) continue;
        const synth::TruthView& view = *found->second;
        capture::Segmentation seg;
        seg.clusterMask = cv::Mat1b::zeros(frame->depth_mm.size());
        const cv::Mat1b read = frame->depth_mm > 0;
        for (const synth::TruthLeaf& leaf : view.leaves) {
            if (leaf.line.size() < 2) continue;
            const cv::Mat1b pixels = (view.labels == leaf.id) & read;
            if (cv::countNonZero(pixels) >= kMinLeafPixels)
                addLeaf(leaf, pixels, frame->intrinsics, seg);
        }
        if (seg.blades.empty()) continue;
        double nearest = 0, farthest = 0;
        cv::minMaxLoc(frame->depth_mm, &nearest, &farthest, nullptr, nullptr, seg.clusterMask);
        seg.tuftNearest_m = static_cast<float>(nearest) / 1000.f;
        seg.tuftFarthest_m = static_cast<float>(farthest) / 1000.f;
        for (std::size_t i = 0; i < seg.blades.size(); ++i) {
            try {
                const modeling::Source src{
                    recording.string(), frame->index, seg.blades[i].id, {}, {}};
                library.archetypes.push_back(
                    modeling::fitSegmentedBlade(seg, i, *frame, fit, src).archetype);
            } catch (const modeling::ModelingError&) {
            }
        }
    }
    return library;
}

}  // namespace meadow::bench
