// Segmentation front end at 640x480 on one core: the whole pipeline per frame (frames/s) and
// each stage's share (counters, ms per frame), with and without PCL, for each plane fitter and
// outlier filter. Plane fitters are also scored for accuracy on the drawn scene: ground pixels
// left in the mask and blade pixels wrongly removed.
#include <benchmark/benchmark.h>

#include <map>

#include "meadow/capture/frame_memory.h"
#include "meadow/capture/recurring_readings.h"
#include "meadow/capture/segmenter.h"
#include "meadow/capture/tuft_motion.h"
#include "support/drawn_tuft.h"

namespace {

using namespace meadow::capture;

const drawn::Drawn& scene() {
    static const drawn::Drawn d = drawn::draw(drawn::fan(9, 65.f), {.sigma_mm = 3.f,
                                                                    .dropoutRate = 0.02f,
                                                                    .flyingPixelRate = 0.3f,
                                                                    .lateralJitter_px = 1,
                                                                    .seed = 5});
    return d;
}

void run(benchmark::State& state, const SegmenterParams& params) {
    const Segmenter segmenter(params);
    const auto& d = scene();
    std::map<std::string, double> stage_ms;
    std::size_t blades = 0;
    for (auto _ : state) {
        const Segmentation s = segmenter.segment(d.frame);
        benchmark::DoNotOptimize(s.blades.data());
        for (const auto& r : s.report) stage_ms[r.stage] += r.time_ms;
        blades = s.blades.size();
    }
    for (const auto& [stage, ms] : stage_ms)
        state.counters[stage + " ms"] = ms / static_cast<double>(state.iterations());
    state.counters["blades"] = static_cast<double>(blades);
    state.counters["frames/s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
    // Accuracy of the ground removal: ground left in the mask, blade pixels lost.
    const Segmentation s = segmenter.segment(d.frame);
    const cv::Mat1b ground = (d.labels == 0) & (d.frame.depth_mm > 0);
    const cv::Mat1b bladesTruth = d.labels > 0;
    state.counters["ground px left"] = cv::countNonZero(ground & s.clusterMask);
    state.counters["blade px lost"] = cv::countNonZero(bladesTruth & ~s.clusterMask);
}

SegmenterParams userBand(PlaneMethod plane,
                         OutlierMethod outliers = OutlierMethod::OrganizedNeighbourhood) {
    SegmenterParams p;
    p.nearDepth_m = 0.9f;  // a user band that holds the tuft and the ground around its base
    p.farDepth_m = 1.2f;
    p.planeMethod = plane;
    p.outlierMethod = outliers;
    return p;
}

void BM_FrontEnd_UserBand_NoPcl(benchmark::State& s) { run(s, userBand(PlaneMethod::None)); }
void BM_FrontEnd_UserBand_Ransac(benchmark::State& s) { run(s, userBand(PlaneMethod::Ransac)); }
void BM_FrontEnd_UserBand_OrganizedMultiPlane(benchmark::State& s) {
    run(s, userBand(PlaneMethod::OrganizedMultiPlane));
}
void BM_FrontEnd_UserBand_NoPcl_StatisticalOutliers(benchmark::State& s) {
    run(s, userBand(PlaneMethod::None, OutlierMethod::Statistical));
}
void BM_FrontEnd_AutoBand_Ransac(benchmark::State& s) {
    SegmenterParams p;
    p.planeMethod = PlaneMethod::Ransac;
    run(s, p);
}
void BM_FrontEnd_AutoBand_OrganizedMultiPlane(benchmark::State& s) {
    SegmenterParams p;
    p.planeMethod = PlaneMethod::OrganizedMultiPlane;
    run(s, p);
}
void BM_FrontEnd_AutoBand_Default(benchmark::State& s) { run(s, SegmenterParams{}); }

// Mask -> blade contours alone (clean-up, contours, partition, flags).
void BM_MaskToBlades(benchmark::State& state) {
    const Segmenter segmenter;
    const cv::Mat1b mask = scene().labels > 0;
    for (auto _ : state) {
        const Segmentation s = segmenter.segmentMask(mask);
        benchmark::DoNotOptimize(s.blades.data());
    }
    state.counters["frames/s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_TemporalFusion5(benchmark::State& state) {
    std::vector<DepthFrame> frames;
    for (unsigned i = 0; i < 5; ++i)
        frames.push_back(
            drawn::draw(drawn::fan(9, 65.f), {.sigma_mm = 3.f, .dropoutRate = 0.1f, .seed = 20 + i})
                .frame);
    const Segmenter segmenter(userBand(PlaneMethod::None));
    for (auto _ : state) {
        const Segmentation s = segmenter.segment(std::span<const DepthFrame>(frames));
        benchmark::DoNotOptimize(s.blades.data());
    }
}

// What capture adds per window of 12 frames (CaptureOptions::recurringFrames): the recurring
// readings over them, and a fused group of 3 segmented with and without them.
std::vector<DepthFrame> twelveFrames() {
    std::vector<DepthFrame> frames;
    for (unsigned i = 0; i < 12; ++i)
        frames.push_back(drawn::draw(drawn::fan(9, 65.f), {.sigma_mm = 3.f,
                                                           .dropoutRate = 0.1f,
                                                           .flyingPixelRate = 0.3f,
                                                           .lateralJitter_px = 1,
                                                           .seed = 40 + i})
                             .frame);
    return frames;
}

void BM_RecurringReadings12(benchmark::State& state) {
    const std::vector<DepthFrame> frames = twelveFrames();
    for (auto _ : state) {
        const RecurringReadings r = recurringReadings(frames);
        benchmark::DoNotOptimize(r.depth_mm.data);
    }
}

// The motion test capture runs on each such window before its recurring readings are used, in
// the band of the window's first segmentation.
void BM_TuftMotion12(benchmark::State& state) {
    const std::vector<DepthFrame> frames = twelveFrames();
    const Segmentation band = Segmenter().segment(std::span<const DepthFrame>(frames.data(), 3));
    for (auto _ : state) {
        const TuftMotion m = tuftMotion(frames, band.nearDepth_m, band.farDepth_m);
        benchmark::DoNotOptimize(m.farChanged);
    }
}

void BM_FusedGroupOf3(benchmark::State& state) {
    const std::vector<DepthFrame> frames = twelveFrames();
    const RecurringReadings tips = state.range(0) ? recurringReadings(frames) : RecurringReadings{};
    const Segmenter segmenter(userBand(PlaneMethod::None));
    const std::span<const DepthFrame> group(frames.data(), 3);
    for (auto _ : state) {
        const Segmentation s = segmenter.segment(group, tips);
        benchmark::DoNotOptimize(s.blades.data());
    }
    state.SetLabel(state.range(0) ? "with recurring readings" : "own readings");
}

// A window of 12 frames segmented once (capture --fuse 12), fused by the median (0) or by the
// nearest recurring readings (1), with the window's recurring readings for the tip trails.
void BM_FusedWindowOf12(benchmark::State& state) {
    const std::vector<DepthFrame> frames = twelveFrames();
    const RecurringReadings tips = recurringReadings(frames);
    SegmenterParams params = userBand(PlaneMethod::None);
    params.fusion = state.range(0) ? FusionMethod::NearestRecurring : FusionMethod::Median;
    const Segmenter segmenter(params);
    for (auto _ : state) {
        const Segmentation s = segmenter.segment(frames, tips);
        benchmark::DoNotOptimize(s.blades.data());
    }
    state.SetLabel(toString(params.fusion));
}

BENCHMARK(BM_FrontEnd_UserBand_NoPcl)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontEnd_UserBand_NoPcl_StatisticalOutliers)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontEnd_UserBand_Ransac)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontEnd_UserBand_OrganizedMultiPlane)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontEnd_AutoBand_Ransac)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontEnd_AutoBand_OrganizedMultiPlane)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontEnd_AutoBand_Default)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MaskToBlades)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TemporalFusion5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RecurringReadings12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TuftMotion12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FusedGroupOf3)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FusedWindowOf12)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

// As the `meadow` command runs: freed frame buffers stay with the process (frame_memory.h).
int main(int argc, char** argv) {
    meadow::capture::keepFrameBuffersResident();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
