#include "meadow/synth/sensor_figures.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>
#include <map>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace meadow::synth {
namespace {

// A reference jump this large (relative to the nearer depth) is an edge that temporal sigma keeps
// away from: the simulated sensor's own definition (sensor_noise_edges.h), which no surface short
// of grazing incidence reaches between neighbours, while even 4 m away one disparity level
// (~5 cm) stays below it.
constexpr float kEdgeRelative = 0.03f;

// See band_mm.
constexpr float kBandRelative = 0.01f;

struct Reference {
    cv::Mat1f depth_mm;  // median of the readings, 0 where under half the frames read
    cv::Mat1b readAll;   // 255 where every frame read
    cv::Mat1f variance;  // sample variance over the frames where readAll (mm^2)
};

Reference makeReference(const std::vector<cv::Mat1w>& frames) {
    const int h = frames.front().rows;
    const int w = frames.front().cols;
    const std::size_t n = frames.size();
    Reference r{cv::Mat1f::zeros(h, w), cv::Mat1b::zeros(h, w), cv::Mat1f::zeros(h, w)};
    std::vector<float> values;
    values.reserve(n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            values.clear();
            for (const cv::Mat1w& f : frames)
                if (f(y, x) != 0) values.push_back(static_cast<float>(f(y, x)));
            if (2 * values.size() < n) continue;
            std::sort(values.begin(), values.end());
            const std::size_t m = values.size();
            r.depth_mm(y, x) =
                m % 2 == 1 ? values[m / 2] : 0.5f * (values[m / 2 - 1] + values[m / 2]);
            if (m != n) continue;
            r.readAll(y, x) = 255;
            double sum = 0.0, sum2 = 0.0;
            for (const float v : values) sum += v;
            const double mean = sum / static_cast<double>(m);
            for (const float v : values) sum2 += (v - mean) * (v - mean);
            r.variance(y, x) = static_cast<float>(sum2 / static_cast<double>(m - 1));
        }
    return r;
}

bool isEdgeJump(float a_mm, float b_mm) {
    if ((a_mm > 0.f) != (b_mm > 0.f)) return true;
    return a_mm > 0.f && std::abs(a_mm - b_mm) > kEdgeRelative * std::min(a_mm, b_mm);
}

std::vector<DepthBinSigma> temporalSigma(const Reference& r, const FigureOptions& o) {
    const int h = r.depth_mm.rows;
    const int w = r.depth_mm.cols;
    cv::Mat1b unsure = r.readAll == 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (x + 1 < w && isEdgeJump(r.depth_mm(y, x), r.depth_mm(y, x + 1)))
                unsure(y, x) = unsure(y, x + 1) = 255;
            if (y + 1 < h && isEdgeJump(r.depth_mm(y, x), r.depth_mm(y + 1, x)))
                unsure(y, x) = unsure(y + 1, x) = 255;
        }
    const int m = o.edgeMargin_px;
    cv::dilate(unsure, unsure, cv::getStructuringElement(cv::MORPH_RECT, {2 * m + 1, 2 * m + 1}));

    const int bins = static_cast<int>(std::lround((o.farthest_m - o.nearest_m) / o.binWidth_m));
    std::vector<double> sum(static_cast<std::size_t>(bins), 0.0);
    std::vector<long> count(static_cast<std::size_t>(bins), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (unsure(y, x) || !r.readAll(y, x)) continue;
            const float z_m = r.depth_mm(y, x) / 1000.f;
            const auto bin = static_cast<int>(std::floor((z_m - o.nearest_m) / o.binWidth_m));
            if (bin < 0 || bin >= bins) continue;
            // Brought to the bin's middle depth as a sensor's sigma grows, with z^2 (the
            // disparity's noise and steps), so that a bin compares sensors, not how two rooms
            // spread their pixels over it: across a 0.5 m bin at 2 m, z^2 alone varies by 1.6.
            const float middle_m = o.nearest_m + (static_cast<float>(bin) + 0.5f) * o.binWidth_m;
            const double toMiddle = std::pow(static_cast<double>(middle_m / z_m), 4.0);
            sum[static_cast<std::size_t>(bin)] += r.variance(y, x) * toMiddle;
            ++count[static_cast<std::size_t>(bin)];
        }
    std::vector<DepthBinSigma> out;
    for (int b = 0; b < bins; ++b) {
        const auto i = static_cast<std::size_t>(b);
        if (count[i] < o.minBinPixels) continue;
        out.push_back({o.nearest_m + static_cast<float>(b) * o.binWidth_m,
                       o.nearest_m + static_cast<float>(b + 1) * o.binWidth_m,
                       std::sqrt(sum[i] / static_cast<double>(count[i])), count[i]});
    }
    return out;
}

// Temporal sigma (mm) at a depth: the bin holding it, else the nearest bin with a figure.
double sigmaAt_mm(const std::vector<DepthBinSigma>& bins, float z_m) {
    const DepthBinSigma* best = nullptr;
    float bestDistance_m = 0.f;
    for (const DepthBinSigma& b : bins) {
        const float d_m = z_m < b.from_m ? b.from_m - z_m : (z_m >= b.to_m ? z_m - b.to_m : 0.f);
        if (best == nullptr || d_m < bestDistance_m) {
            best = &b;
            bestDistance_m = d_m;
        }
    }
    return best == nullptr ? 0.0 : best->sigma_mm;
}

// One depth step seen along a scan line (a row for a vertical edge, a column for a horizontal
// one): `line` indexes the scan line, `at` the pixel just before the step along it.
struct Step {
    int line = 0;
    int at = 0;
    bool nearFirst = true;  // the near side comes first along the scan line
    float near_mm = 0.f;
    float far_mm = 0.f;
};

// Pixel `k` of scan line `line` (rows when `alongRows`, else columns).
struct ScanLines {
    bool alongRows;
    int lines;
    int length;
    [[nodiscard]] cv::Point pixel(int line, int k) const {
        return alongRows ? cv::Point{k, line} : cv::Point{line, k};
    }
};

// The median of the readings of pixels `from`..`to` along the scan line over the frames, 0 when
// fewer than half of them read.
float sideDepth_mm(const std::vector<cv::Mat1w>& frames, const ScanLines& s, int line, int from,
                   int to) {
    std::vector<float> values;
    int possible = 0;
    for (int k = std::min(from, to); k <= std::max(from, to); ++k) {
        if (k < 0 || k >= s.length) return 0.f;
        const cv::Point p = s.pixel(line, k);
        for (const cv::Mat1w& f : frames) {
            ++possible;
            if (f(p) != 0) values.push_back(static_cast<float>(f(p)));
        }
    }
    if (2 * static_cast<int>(values.size()) < possible) return 0.f;
    const auto mid = values.begin() + static_cast<long>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

// Least difference that makes a step between depths a and b: step_mm, and never less than the
// edge jump, so that a surface seen at a slant far away (one disparity level per pixel) is a
// ramp, not a run of steps.
float stepAt_mm(float a_mm, float b_mm, const FigureOptions& o) {
    return std::max(o.step_mm, kEdgeRelative * std::min(a_mm, b_mm));
}

std::vector<Step> findSteps(const std::vector<cv::Mat1w>& frames, const Reference& r,
                            const ScanLines& s, const FigureOptions& o) {
    std::vector<Step> steps;
    const int z = o.zone_px;
    for (int line = 0; line < s.lines; ++line)
        for (int k = z + 1; k + z + 2 < s.length; ++k) {
            const float a_mm = r.depth_mm(s.pixel(line, k));
            const float b_mm = r.depth_mm(s.pixel(line, k + 1));
            if (a_mm <= 0.f || b_mm <= 0.f || std::abs(a_mm - b_mm) <= stepAt_mm(a_mm, b_mm, o))
                continue;
            // Sides: the two pixels just beyond the zone on either side.
            const float before_mm = sideDepth_mm(frames, s, line, k - z, k - z - 1);
            const float after_mm = sideDepth_mm(frames, s, line, k + 1 + z, k + 2 + z);
            if (before_mm <= 0.f || after_mm <= 0.f) continue;
            const bool nearFirst = a_mm < b_mm;
            Step step{line, k, nearFirst, nearFirst ? before_mm : after_mm,
                      nearFirst ? after_mm : before_mm};
            if (step.far_mm - step.near_mm <= stepAt_mm(step.near_mm, step.far_mm, o))
                continue;  // a ramp, not a step
            steps.push_back(step);
        }
    return steps;
}

// Half-width of the band of readings that belong to a side at depth z: mixedSigmas temporal
// sigmas, and at least kBandRelative of the depth, which covers a slanted side's change over
// the 1-3 px between its sample pixels and the zone.
double band_mm(const std::vector<DepthBinSigma>& sigma, float z_mm, const FigureOptions& o) {
    return std::max(o.mixedSigmas * sigmaAt_mm(sigma, z_mm / 1000.f),
                    static_cast<double>(kBandRelative * z_mm));
}

struct MixedCount {
    long readings = 0;
    long mixed = 0;
};

void countMixed(const std::vector<cv::Mat1w>& frames, const Reference& r,
                const std::vector<Step>& steps, const ScanLines& s,
                const std::vector<DepthBinSigma>& sigma, const FigureOptions& o, cv::Mat1b& counted,
                MixedCount& out) {
    for (const Step& step : steps) {
        const double nearBand_mm = band_mm(sigma, step.near_mm, o);
        const double farBand_mm = band_mm(sigma, step.far_mm, o);
        if (step.near_mm + nearBand_mm >= step.far_mm - farBand_mm) continue;
        // Only sides that are flat across the step: on a slanted side, the zone's readings of
        // that very surface would leave its band.
        const auto flat = [&](int k0, int k1, double band) {
            return std::abs(r.depth_mm(s.pixel(step.line, k0)) -
                            r.depth_mm(s.pixel(step.line, k1))) <= 0.5 * band;
        };
        const int z = o.zone_px;
        const double beforeBand_mm = step.nearFirst ? nearBand_mm : farBand_mm;
        const double afterBand_mm = step.nearFirst ? farBand_mm : nearBand_mm;
        if (!flat(step.at - z, step.at - z - 1, beforeBand_mm) ||
            !flat(step.at + z + 1, step.at + z + 2, afterBand_mm))
            continue;
        for (int k = step.at - o.zone_px + 1; k <= step.at + o.zone_px; ++k) {
            const cv::Point p = s.pixel(step.line, k);
            if (counted(p)) continue;
            counted(p) = 255;
            for (const cv::Mat1w& f : frames) {
                if (f(p) == 0) continue;
                const double d_mm = f(p);
                ++out.readings;
                if (std::abs(d_mm - step.near_mm) > nearBand_mm &&
                    std::abs(d_mm - step.far_mm) > farBand_mm)
                    ++out.mixed;
            }
        }
    }
}

struct RunCount {
    long runs = 0;
    long runPixels = 0;
    long steps = 0;
};

// Chains of steps in consecutive scan lines within 1 px of one another, the near side on the
// same side; each chain's displacements per frame are cut into runs of one sign.
void countRuns(const std::vector<cv::Mat1w>& frames, const std::vector<Step>& steps,
               const ScanLines& s, const FigureOptions& o, RunCount& out) {
    const int half = o.zone_px + 2;  // the zone and both side pixels on each side
    // Displacement of one step in each frame.
    const auto displacement = [&](const Step& step) {
        std::vector<double> nearCount;
        nearCount.reserve(frames.size());
        const float middle_mm = 0.5f * (step.near_mm + step.far_mm);
        for (const cv::Mat1w& f : frames) {
            int c = 0;
            for (int k = step.at - half + 1; k <= step.at + half; ++k) {
                const std::uint16_t d = f(s.pixel(step.line, k));
                c += d != 0 && static_cast<float>(d) < middle_mm;
            }
            nearCount.push_back(c);
        }
        double mean = 0.0;
        for (const double c : nearCount) mean += c;
        mean /= static_cast<double>(nearCount.size());
        for (double& c : nearCount) c -= mean;
        return nearCount;
    };
    // Steps by scan line, then linked to the nearest step of the next line.
    std::map<int, std::vector<const Step*>> byLine;
    for (const Step& step : steps) byLine[step.line].push_back(&step);
    std::map<const Step*, bool> used;
    for (const auto& [line, starts] : byLine)
        for (const Step* start : starts) {
            if (used[start]) continue;
            std::vector<const Step*> chain{start};
            used[start] = true;
            for (;;) {
                const Step* last = chain.back();
                const auto next = byLine.find(last->line + 1);
                if (next == byLine.end()) break;
                const Step* best = nullptr;
                for (const Step* c : next->second)
                    if (!used[c] && c->nearFirst == last->nearFirst &&
                        std::abs(c->at - last->at) <= 1 &&
                        (best == nullptr ||
                         std::abs(c->at - last->at) < std::abs(best->at - last->at)))
                        best = c;
                if (best == nullptr) break;
                used[best] = true;
                chain.push_back(best);
            }
            if (static_cast<int>(chain.size()) < o.minEdgeLength_px) continue;
            out.steps += static_cast<long>(chain.size());
            std::vector<std::vector<double>> moves;
            moves.reserve(chain.size());
            for (const Step* step : chain) moves.push_back(displacement(*step));
            for (std::size_t f = 0; f < frames.size(); ++f) {
                int sign = 0;
                for (const std::vector<double>& m : moves) {
                    // The near side's count grows as the edge moves into the far side; which
                    // way that is along the scan line does not matter for the sign's runs.
                    const int now = m[f] > 1e-9 ? 1 : (m[f] < -1e-9 ? -1 : 0);
                    if (now != 0 && now != sign) ++out.runs;
                    if (now != 0) ++out.runPixels;
                    sign = now;
                }
            }
        }
}

// The mesh turned by angle_deg about the vertical (y) axis through the centre of its bounds.
LabelledMesh turned(LabelledMesh mesh, float angle_deg) {
    glm::vec3 lo = mesh.positions_m.front();
    glm::vec3 hi = lo;
    for (const glm::vec3& p : mesh.positions_m) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float a = glm::radians(angle_deg);
    for (glm::vec3& p : mesh.positions_m) {
        const glm::vec3 d = p - centre;
        p = centre + glm::vec3{std::cos(a) * d.x + std::sin(a) * d.z, d.y,
                               -std::sin(a) * d.x + std::cos(a) * d.z};
    }
    return mesh;
}

}  // namespace

SensorFigures measureSensorFigures(const std::vector<cv::Mat1w>& frames_mm,
                                   const FigureOptions& options) {
    if (frames_mm.size() < 2)
        throw std::invalid_argument("measureSensorFigures: needs at least 2 frames, got " +
                                    std::to_string(frames_mm.size()));
    for (const cv::Mat1w& f : frames_mm)
        if (f.size() != frames_mm.front().size() || f.empty())
            throw std::invalid_argument("measureSensorFigures: frames differ in size or are empty");
    const Reference r = makeReference(frames_mm);
    SensorFigures figures;
    figures.temporalSigma = temporalSigma(r, options);

    const int h = r.depth_mm.rows;
    const int w = r.depth_mm.cols;
    cv::Mat1b counted = cv::Mat1b::zeros(h, w);
    MixedCount mixed;
    RunCount runs;
    for (const ScanLines s : {ScanLines{true, h, w}, ScanLines{false, w, h}}) {
        const std::vector<Step> steps = findSteps(frames_mm, r, s, options);
        countMixed(frames_mm, r, steps, s, figures.temporalSigma, options, counted, mixed);
        countRuns(frames_mm, steps, s, options, runs);
    }
    figures.zoneReadings = mixed.readings;
    figures.mixedShare =
        mixed.readings > 0 ? static_cast<double>(mixed.mixed) / static_cast<double>(mixed.readings)
                           : 0.0;
    figures.edgeRuns = runs.runs;
    figures.edgeSteps = runs.steps;
    figures.edgeRunLength_px =
        runs.runs > 0 ? static_cast<double>(runs.runPixels) / static_cast<double>(runs.runs) : 0.0;
    return figures;
}

std::vector<LabelledMesh> calibrationRoom() {
    // Laid out after the real recording's reference image: the camera 0.9 m above the floor (y
    // down) looking level along +z; a back wall with a concave corner at 3-4.4 m, a door panel
    // at 1 m on the left with low boxes before it, a chair-like block at 2.75 m, a desk at 2 m
    // and a wardrobe at 1.3 m on the right.
    constexpr float kFloor_m = 0.9f;
    constexpr float kCeiling_m = -1.2f;
    constexpr float kFar_m = 8.f;  // planes run on behind what hides them
    std::vector<LabelledMesh> room;
    LabelledMesh shell;
    shell.label = 1;
    addQuad(shell, {-4.f, kFloor_m, 0.3f}, {4.f, kFloor_m, 0.3f}, {4.f, kFloor_m, kFar_m},
            {-4.f, kFloor_m, kFar_m});
    addQuad(shell, {-4.f, kCeiling_m, 0.3f}, {4.f, kCeiling_m, 0.3f}, {4.f, kCeiling_m, kFar_m},
            {-4.f, kCeiling_m, kFar_m});
    // Two walls meeting at (1.2, 4.4), each carried on past the corner behind the other.
    const auto wall = [&](glm::vec2 a, glm::vec2 b) {
        addQuad(shell, {a.x, kCeiling_m, a.y}, {b.x, kCeiling_m, b.y}, {b.x, kFloor_m, b.y},
                {a.x, kFloor_m, a.y});
    };
    wall({-2.4f, 2.82f}, {2.4f, 4.92f});
    wall({0.2f, 5.1f}, {3.f, 3.16f});
    room.push_back(shell);
    // Each box is turned a few degrees about its vertical axis, as furniture stands: a face
    // parallel to the image would hold one depth, so all its pixels would sit at one point
    // between two disparity levels and its temporal sigma would depend on where that is.
    room.push_back(turned(boxMesh({-0.8f, -1.2f, 1.0f}, {-0.364f, 0.09f, 1.3f}, 2), 8.f));  // door
    room.push_back(turned(boxMesh({-0.45f, 0.06f, 0.65f}, {-0.25f, kFloor_m, 0.8f}, 3), -6.f));
    room.push_back(turned(boxMesh({-0.28f, 0.085f, 0.8f}, {-0.14f, kFloor_m, 1.0f}, 4), 10.f));
    room.push_back(
        turned(boxMesh({-0.28f, -0.05f, 2.75f}, {0.1f, kFloor_m, 3.1f}, 5), -9.f));  // chair
    room.push_back(
        turned(boxMesh({0.45f, -0.6f, 1.3f}, {1.0f, kFloor_m, 1.8f}, 6), -7.f));  // wardrobe
    room.push_back(turned(boxMesh({0.22f, 0.25f, 2.1f}, {0.7f, kFloor_m, 2.6f}, 7), -8.f));  // desk
    return room;
}

std::vector<cv::Mat1w> renderStillFrames(const SimulatedSensor& sensor,
                                         const std::vector<LabelledMesh>& scene, int count,
                                         std::uint64_t seed) {
    std::vector<cv::Mat1w> frames;
    frames.reserve(static_cast<std::size_t>(std::max(count, 0)));
    for (int i = 0; i < count; ++i)
        frames.push_back(sensor.render(scene, seed + static_cast<std::uint64_t>(i)).depth_mm);
    return frames;
}

}  // namespace meadow::synth
