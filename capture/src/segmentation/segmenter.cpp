// Segmenter: runs the stages of capture/src/segmentation/ in order and collects their reports.
#include "meadow/capture/segmenter.h"

#include <pcl/console/print.h>

#include <chrono>
#include <cmath>
#include <numeric>
#include <opencv2/core.hpp>
#include <sstream>

#include "meadow/capture/error.h"
#include "segmentation/stages.h"

namespace meadow::capture {

namespace seg = segmentation;

namespace {
// Sanity limits for parameters: beyond them a value is a typo, not a choice.
constexpr float kMaxDepth_m = 20.0f;
constexpr int kMaxKernel_px = 101;
constexpr int kMaxIterations = 100000;

std::string mustBe(const char* name, const std::string& what, double value) {
    std::ostringstream s;
    s << "SegmenterParams::" << name << " must be " << what << ", got " << value;
    return s.str();
}
}  // namespace

void SegmenterParams::setSubject(Subject subject) {
    const bool plant = subject == Subject::PottedPlant;
    plantFinding = plant ? PlantFinding::Clusters : PlantFinding::DepthMode;
    partition = plant ? PartitionMethod::StemGraph : PartitionMethod::Contour;
}

std::string SegmenterParams::problem() const {
    const struct {
        const char* name;
        float value;
        float lo, hi;
    } ranges[] = {
        {"nearDepth_m", nearDepth_m, 0.f, kMaxDepth_m},
        {"farDepth_m", farDepth_m, 0.f, kMaxDepth_m},
        {"histogramBin_m", histogramBin_m, 1e-4f, 1.f},
        {"minModeFraction", minModeFraction, 0.f, 1.f},
        {"maxBandHalfWidth_m", maxBandHalfWidth_m, 1e-3f, kMaxDepth_m},
        {"bandGrowStep_m", bandGrowStep_m, 0.f, 1.f},
        {"planeDistance_m", planeDistance_m, 1e-4f, 1.f},
        {"minPlaneFraction", minPlaneFraction, 0.f, 1.f},
        {"maxGroundTilt_deg", maxGroundTilt_deg, 0.f, 90.f},
        {"outlierDepthTolerance_m", outlierDepthTolerance_m, 1e-4f, 1.f},
        {"statisticalStddevMul", statisticalStddevMul, 0.f, 100.f},
        {"minValidFrameFraction", minValidFrameFraction, 0.f, 1.f},
        {"fusionRecurringShare", fusionRecurringShare, 0.f, 1.f},
        {"baseBandFraction", baseBandFraction, 0.f, 1.f},
        {"smoothingSigma_px", smoothingSigma_px, 0.f, 1000.f},
        {"edgeSmoothingSigma_px", edgeSmoothingSigma_px, 0.f, 20.f},
        {"edgeSmoothingMaxShift_px", edgeSmoothingMaxShift_px, 0.f, 5.f},
        {"tipTrailMinReach_px", tipTrailMinReach_px, 0.f, 1000.f},
        {"tipTrailMaxRaggedness", tipTrailMaxRaggedness, 0.f, 1.f},
        {"minPersistence_px", minPersistence_px, 0.f, 1e5f},
        {"minPersistenceFraction", minPersistenceFraction, 0.f, 1.f},
        {"minResolvableWidth_px", minResolvableWidth_px, 0.f, 1000.f},
        {"minInteriorFraction", minInteriorFraction, 0.f, 1.f},
        {"raggedEdges", raggedEdges, 0.f, 1.f},
        {"curlTurn_deg", curlTurn_deg, 0.f, 3600.f},
        {"overlapWidthRatio", overlapWidthRatio, 1.f, 1000.f},
        {"secondTipFraction", secondTipFraction, 0.f, 1.f},
        {"forkDepthSigma_mm", forkDepthSigma_mm, 0.1f, 1000.f},
        {"forkMaxRaggedness", forkMaxRaggedness, 0.f, 1.f},
        {"fragmentLinkGap_px", fragmentLinkGap_px, 0.f, 100.f},
        {"fragmentMinAspect", fragmentMinAspect, 1.f, 1000.f},
        {"fragmentLinkAngle_deg", fragmentLinkAngle_deg, 0.f, 90.f},
        {"sceneMaxDepth_m", sceneMaxDepth_m, 0.1f, kMaxDepth_m},
        {"scenePlaneDistance_m", scenePlaneDistance_m, 1e-4f, 1.f},
        {"minScenePlaneShare", minScenePlaneShare, 0.f, 1.f},
        {"clusterTolerance_m", clusterTolerance_m, 1e-3f, 1.f},
        {"plantMaxMeanWidth_m", plantMaxMeanWidth_m, 1e-3f, 10.f},
        {"plantMinHeight_m", plantMinHeight_m, 0.f, 10.f},
        {"plantMinImageShare", plantMinImageShare, 0.f, 1.f},
        {"plantMinSolidAngle_sr", plantMinSolidAngle_sr, 0.f, 12.57f},
        {"minLeafBranch_px", minLeafBranch_px, 0.f, 10000.f},
        {"crossingMaxBend_deg", crossingMaxBend_deg, 0.f, 180.f},
        {"crossingDepthStep_mm", crossingDepthStep_mm, 0.f, 100000.f},
        {"leafGapBridge_m", leafGapBridge_m, 0.f, 1.f},
    };
    for (const auto& r : ranges) {
        if (!std::isfinite(r.value))
            return std::string("SegmenterParams::") + r.name + " is not finite";
        if (r.value < r.lo || r.value > r.hi)
            return mustBe(r.name, "in [" + std::to_string(r.lo) + ", " + std::to_string(r.hi) + "]",
                          r.value);
    }
    if ((nearDepth_m > 0.f || farDepth_m > 0.f) && !(nearDepth_m < farDepth_m))
        return "SegmenterParams: nearDepth_m (" + std::to_string(nearDepth_m) +
               ") must be below farDepth_m (" + std::to_string(farDepth_m) +
               "), or both 0 for an automatic band";
    const struct {
        const char* name;
        int value, lo, hi;
    } ints[] = {
        {"maxPlanes", maxPlanes, 0, 10},
        {"planeSampleStride_px", planeSampleStride_px, 1, 64},
        {"ransacIterations", ransacIterations, 1, kMaxIterations},
        {"outlierWindow_px", outlierWindow_px, 3, kMaxKernel_px},
        {"outlierMinNeighbours", outlierMinNeighbours, 0, kMaxKernel_px * kMaxKernel_px},
        {"statisticalMeanK", statisticalMeanK, 1, 1000},
        {"closeKernel_px", closeKernel_px, 0, kMaxKernel_px},
        {"openKernel_px", openKernel_px, 0, kMaxKernel_px},
        {"minRegionArea_px", minRegionArea_px, 0, 1 << 28},
        {"maxHoleArea_px", maxHoleArea_px, 0, 1 << 28},
        {"minBladeContour_px", minBladeContour_px, 3, 1 << 20},
        {"tipTrailGap_px", tipTrailGap_px, 1, 16},
        {"tipTrailMaxLength_px", tipTrailMaxLength_px, 0, 4096},
        {"fragmentMaxArea_px", fragmentMaxArea_px, 0, 1 << 28},
        {"fusionAgreement_mm", fusionAgreement_mm, 0, 1000},
        {"maxScenePlanes", maxScenePlanes, 0, 10},
        {"minClusterPoints", minClusterPoints, 1, 1 << 24},
    };
    for (const auto& r : ints)
        if (r.value < r.lo || r.value > r.hi)
            return mustBe(r.name, "in [" + std::to_string(r.lo) + ", " + std::to_string(r.hi) + "]",
                          r.value);
    if (outlierWindow_px % 2 == 0) return mustBe("outlierWindow_px", "odd", outlierWindow_px);
    return {};
}

std::vector<cv::Point> Segmentation::cutPoints_px() const {
    std::vector<cv::Point> cuts;
    for (const auto& c : clusters)
        for (int i : c.cutIndices) cuts.push_back(c.contour_px[static_cast<size_t>(i)]);
    return cuts;
}

double Segmentation::totalTime_ms() const {
    double t = 0.0;
    for (const auto& r : report) t += r.time_ms;
    return t;
}

std::string Segmentation::summary() const {
    std::ostringstream s;
    s << blades.size() << " blade(s) in " << clusters.size() << " cluster(s), band [" << nearDepth_m
      << ", " << farDepth_m << "] m, edges ragged " << std::lround(1000.0 * edgeRaggedness) / 10.0
      << " %";
    if (!noBladesReason.empty()) s << "; no blades found: " << noBladesReason;
    s << '\n';
    for (const auto& r : report) {
        s << "  " << r.stage << ": dropped " << r.droppedPixels << " px, kept " << r.keptPixels
          << " px, " << r.time_ms << " ms\n";
        for (const auto& n : r.notes) s << "    " << n << '\n';
    }
    for (const auto& c : clusters)
        for (const auto& why : c.reasons) s << "  cluster: " << why << '\n';
    for (const auto& b : blades)
        for (const auto& why : b.reasons) s << "  blade " << b.id << ": " << why << '\n';
    return s.str();
}

struct Segmenter::Impl {
    SegmenterParams params;

    // Times a stage and records the mask's change.
    template <class F>
    void stage(Segmentation& out, const char* name, const cv::Mat1b* mask, F&& body) const {
        StageReport r;
        r.stage = name;
        const int before = mask && !mask->empty() ? cv::countNonZero(*mask) : 0;
        const auto t0 = std::chrono::steady_clock::now();
        body(r);
        r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
        if (mask && !mask->empty()) {
            r.keptPixels = cv::countNonZero(*mask);
            if (r.droppedPixels == 0) r.droppedPixels = std::max(0, before - r.keptPixels);
        }
        out.report.push_back(std::move(r));
    }

    // `recurring`: readings that recur over more frames than `depth_mm` fuses (may be empty);
    // they join the tip trails' candidates only.
    Segmentation fromDepth(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                           Segmentation out, const cv::Mat1w& recurring = cv::Mat1w()) const {
        if (cv::countNonZero(depth_mm) == 0) {
            out.noBladesReason = "the frame has no depth readings (all pixels are 0)";
            out.clusterMask = cv::Mat1b::zeros(depth_mm.size());
            return out;
        }
        seg::DepthBand band;
        band.near_m = params.nearDepth_m;
        band.far_m = params.farDepth_m;
        band.found = params.nearDepth_m < params.farDepth_m;
        const bool userBand = band.found;
        const bool removePlanes = params.planeMethod != PlaneMethod::None && params.maxPlanes > 0;
        if (!userBand && params.plantFinding == PlantFinding::Clusters)
            return fromPlant(depth_mm, intrinsics, std::move(out));
        cv::Mat1b mask;
        // With a user band the band goes first (fewer points for the plane fit). Without one the
        // ground is removed first: a side-viewed ground plane spreads over every depth from the
        // bottom row outwards and its nearest part would otherwise be the nearest dominant mode.
        if (userBand) {
            stage(out, "depth band", &mask, [&](StageReport& r) {
                r.notes.push_back("user band");
                mask = seg::depthBandMask(depth_mm, band, r);
            });
        } else {
            mask = depth_mm > 0;
        }
        const bool trails = params.tipTrailMinReach_px > 0.f;
        // What the plane fit removes stays removed from the recurring readings too.
        cv::Mat1b removedAsPlane;
        if (removePlanes) {
            if (trails && !recurring.empty()) removedAsPlane = mask.clone();
            stage(out, "plane removal", &mask, [&](StageReport& r) {
                out.groundPlane = seg::removePlanes(depth_mm, intrinsics, params, mask, r);
            });
            if (!removedAsPlane.empty()) removedAsPlane &= ~mask;
        }
        if (!userBand) {
            stage(out, "depth band", &mask, [&](StageReport& r) {
                band = seg::automaticDepthBand(depth_mm, mask, intrinsics, params,
                                               out.groundPlane.has_value(), r);
                if (band.found) {
                    cv::Mat1b inBand = seg::depthBandMask(depth_mm, band, r);
                    if (!band.scenery.empty()) mask &= ~band.scenery;
                    inBand &= mask;
                    seg::growDepthContinuous(depth_mm, mask, band, params, inBand, r);
                    mask = inBand;
                } else {
                    mask.setTo(0);
                }
            });
        }
        out.nearDepth_m = band.near_m;
        out.farDepth_m = band.far_m;
        if (!band.found) {
            out.noPlant = !band.notLeaves.empty();
            out.noBladesReason =
                out.noPlant ? "no plant in view: the nearest object, " + band.notLeaves
                            : "no depth mode holds enough pixels to be a tuft (see report)";
            out.clusterMask = cv::Mat1b::zeros(depth_mm.size());
            return out;
        }
        if (cv::countNonZero(mask) > 0) {
            double nearest_mm = 0.0, farthest_mm = 0.0;
            cv::minMaxLoc(depth_mm, &nearest_mm, &farthest_mm, nullptr, nullptr, mask);
            out.tuftNearest_m = static_cast<float>(nearest_mm) / seg::kMillimetresPerMetre;
            out.tuftFarthest_m = static_cast<float>(farthest_mm) / seg::kMillimetresPerMetre;
        }
        // Every in-band reading, for the tip trails the next stages would drop, and the in-band
        // recurring readings besides.
        const cv::Mat1b inBand = trails ? mask.clone() : cv::Mat1b();
        cv::Mat1b recurringInBand;
        if (trails && !recurring.empty()) {
            StageReport unused;  // the band's own report is the depth band stage's
            recurringInBand = seg::depthBandMask(recurring, band, unused);
            if (!band.scenery.empty()) recurringInBand &= ~band.scenery;
            if (!removedAsPlane.empty()) recurringInBand &= ~removedAsPlane;
        }
        if (params.outlierMethod != OutlierMethod::None)
            stage(out, "outlier removal", &mask, [&](StageReport& r) {
                seg::removeOutliers(depth_mm, intrinsics, params, mask, r);
            });
        return fromMask(std::move(mask), std::move(out), seg::SensedExtent::of(depth_mm), inBand,
                        depth_mm, recurringInBand);
    }

    // PlantFinding::Clusters: the plant found among the scene's objects takes the depth band's
    // place; the rest is as for a band.
    Segmentation fromPlant(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                           Segmentation out) const {
        seg::FoundPlant plant;
        cv::Mat1b mask;
        stage(out, "plant finding", &mask, [&](StageReport& r) {
            plant = seg::findPlant(depth_mm, intrinsics, params, r);
            mask = plant.found ? plant.mask : cv::Mat1b::zeros(depth_mm.size());
        });
        out.leftOut = std::move(plant.leftOut);
        if (!plant.found) {
            out.noBladesReason = plant.whyNot;
            out.noPlant = true;
            out.clusterMask = cv::Mat1b::zeros(depth_mm.size());
            return out;
        }
        out.plantBase_px = plant.base_px;
        out.plantPot_px = plant.pot_px;
        out.nearDepth_m = out.tuftNearest_m = plant.near_m;
        out.farDepth_m = out.tuftFarthest_m = plant.far_m;
        const bool trails = params.tipTrailMinReach_px > 0.f;
        if (params.outlierMethod != OutlierMethod::None)
            stage(out, "outlier removal", &mask, [&](StageReport& r) {
                seg::removeOutliers(depth_mm, intrinsics, params, mask, r);
            });
        return fromMask(std::move(mask), std::move(out), seg::SensedExtent::of(depth_mm),
                        trails ? plant.candidates : cv::Mat1b(), depth_mm, cv::Mat1b(),
                        &intrinsics);
    }

    // `sensed`: where the sensor read anything (the whole frame for a given mask).
    // `readings`: the in-band readings before outlier removal, `depth_mm` the depth (both empty
    // for a given mask); `recurring`: in-band readings recurring over more frames (may be empty);
    // `intrinsics`: the camera's, where the plant was found in the scene (else null).
    Segmentation fromMask(cv::Mat1b mask, Segmentation out, const seg::SensedExtent& sensed,
                          const cv::Mat1b& readings = cv::Mat1b(),
                          const cv::Mat1w& depth_mm = cv::Mat1w(),
                          const cv::Mat1b& recurring = cv::Mat1b(),
                          const Intrinsics* intrinsics = nullptr) const {
        // Clean-up and contours work inside the region the mask can reach, not the whole frame:
        // a tuft covers a small part of it, and the results are the same (cleanUpRegion).
        const cv::Rect cleaned = seg::cleanUpRegion(mask, params);
        cv::Mat1b local = cleaned.empty() ? cv::Mat1b() : cv::Mat1b(mask(cleaned).clone());
        stage(out, "clean-up", &local, [&](StageReport& r) {
            if (!local.empty()) seg::cleanUpMask(params, local, r);
        });
        mask.setTo(0);
        if (!local.empty()) local.copyTo(mask(cleaned));
        cv::Rect region = cleaned;
        seg::TipTrails trails;
        if (!readings.empty())
            stage(out, "tip trails", &mask, [&](StageReport& r) {
                if (!recurring.empty())
                    r.notes.push_back(std::to_string(cv::countNonZero(recurring & ~readings)) +
                                      " px of in-band readings that recur over " +
                                      std::to_string(out.recurringFrames) +
                                      " frames join this segmentation's own as trail candidates");
                trails = seg::recoverTipTrails(readings, recurring, params, mask, r);
                region |= trails.box;
                out.edgeRaggedness = trails.raggedness;
            });
        if (intrinsics && params.partition == PartitionMethod::StemGraph)
            stage(out, "leaf gaps", &mask, [&](StageReport& r) {
                seg::bridgeLeafGaps(mask, depth_mm, *intrinsics, params, r);
            });
        out.clusterMask = mask;
        stage(out, "contours", &local, [&](StageReport& r) {
            out.clusters = seg::extractClusters(mask, region, sensed, params, r);
        });
        stage(out, "partition", nullptr, [&](StageReport& r) {
            // The largest cluster first: the one that holds the stem, by which leaves cut off
            // from it in clusters of their own are based.
            std::vector<std::size_t> order(out.clusters.size());
            std::iota(order.begin(), order.end(), std::size_t{0});
            if (params.partition == PartitionMethod::StemGraph)
                std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
                    return out.clusters[a].area_px > out.clusters[b].area_px;
                });
            std::vector<cv::Point> plantStem_px;
            for (const std::size_t c : order) {
                BladeCluster& cluster = out.clusters[c];
                const int firstId = static_cast<int>(out.blades.size()) + 1;
                auto blades =
                    params.partition == PartitionMethod::StemGraph
                        ? seg::partitionByStem(cluster, mask, depth_mm, params, firstId,
                                               out.plantBase_px, out.plantPot_px, plantStem_px, r)
                        : seg::partitionCluster(cluster, mask, depth_mm, out.edgeRaggedness, params,
                                                firstId, r);
                if (plantStem_px.empty()) plantStem_px = cluster.stemLine_px;
                if (params.partition != PartitionMethod::StemGraph)
                    seg::flagCutCrossings(blades, cluster, mask, depth_mm, params);
                seg::flagBlades(blades, cluster, mask.size(), sensed, params, out.edgeRaggedness);
                for (auto& b : blades) {
                    const auto tip = static_cast<size_t>(b.tipIndex);
                    b.tipOnTrail = tip < b.contour_px.size() && trails.holds(b.contour_px[tip]);
                    cluster.bladeIds.push_back(b.id);
                    out.blades.push_back(std::move(b));
                }
            }
        });
        if (out.blades.empty() && out.noBladesReason.empty())
            out.noBladesReason = cv::countNonZero(mask) == 0
                                     ? "the mask is empty after clean-up (see report)"
                                     : "no region is large enough to hold a blade";
        return out;
    }
};

Segmenter::Segmenter(SegmenterParams params) : impl_(std::make_unique<Impl>()) {
    if (auto why = params.problem(); !why.empty())
        throw CaptureError(why + "; fix the segmentation parameters");
    impl_->params = params;
    // PCL reports on the console (a RANSAC sample it finds collinear, ...); the segmenter
    // reports through its stage notes and errors, one line per failure.
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

const SegmenterParams& Segmenter::params() const { return impl_->params; }

namespace {
void checkFrame(const DepthFrame& f) {
    if (f.depth_mm.empty())
        throw CaptureError("Segmenter: depth frame " + std::to_string(f.index) +
                           " is empty; pass a frame read from a depth source");
    if (auto why = f.intrinsics.problem(); !why.empty())
        throw CaptureError("Segmenter: frame " + std::to_string(f.index) +
                           " has unusable intrinsics: " + why);
    if (f.depth_mm.cols != f.intrinsics.width_px || f.depth_mm.rows != f.intrinsics.height_px)
        throw CaptureError("Segmenter: frame " + std::to_string(f.index) + " is " +
                           std::to_string(f.depth_mm.cols) + "x" + std::to_string(f.depth_mm.rows) +
                           " px but its intrinsics say " + std::to_string(f.intrinsics.width_px) +
                           "x" + std::to_string(f.intrinsics.height_px) +
                           "; fix the source's intrinsics");
}
}  // namespace

Segmentation Segmenter::segment(const DepthFrame& frame) const {
    checkFrame(frame);
    return impl_->fromDepth(frame.depth_mm, frame.intrinsics, {});
}

Segmentation Segmenter::segment(std::span<const DepthFrame> frames) const {
    return segment(frames, RecurringReadings{});
}

Segmentation Segmenter::segment(std::span<const DepthFrame> frames,
                                const RecurringReadings& tips) const {
    if (frames.empty())
        throw CaptureError("Segmenter: no frames given; pass at least one depth frame");
    for (const auto& f : frames) {
        checkFrame(f);
        if (f.depth_mm.size() != frames[0].depth_mm.size() ||
            !(f.intrinsics == frames[0].intrinsics))
            throw CaptureError("Segmenter: frame " + std::to_string(f.index) +
                               " differs in size or intrinsics from frame " +
                               std::to_string(frames[0].index) +
                               "; temporal fusion needs frames of one camera");
    }
    if (!tips.depth_mm.empty() && tips.depth_mm.size() != frames[0].depth_mm.size())
        throw CaptureError(
            "Segmenter: the recurring readings are " + std::to_string(tips.depth_mm.cols) + "x" +
            std::to_string(tips.depth_mm.rows) + " px but frame " +
            std::to_string(frames[0].index) + " is " + std::to_string(frames[0].depth_mm.cols) +
            "x" + std::to_string(frames[0].depth_mm.rows) +
            "; take them over frames of the same camera");
    Segmentation out;
    if (!tips.depth_mm.empty()) out.recurringFrames = tips.frames;
    if (frames.size() == 1)
        return impl_->fromDepth(frames[0].depth_mm, frames[0].intrinsics, std::move(out),
                                tips.depth_mm);
    cv::Mat1w fused;
    impl_->stage(out, "temporal fusion", nullptr,
                 [&](StageReport& r) { fused = seg::fuseFrames(frames, impl_->params, r); });
    return impl_->fromDepth(fused, frames[0].intrinsics, std::move(out), tips.depth_mm);
}

Segmentation Segmenter::segmentMask(const cv::Mat1b& mask) const {
    if (mask.empty()) throw CaptureError("Segmenter::segmentMask: the mask is empty (0x0)");
    cv::Mat1b binary = mask > 0;
    return impl_->fromMask(binary, {}, seg::SensedExtent::whole(binary.size()));
}

}  // namespace meadow::capture
