// The face's turn about the spine, read from the depth across the blade (blade_fit.h, fitTwist).
#include <algorithm>
#include <cmath>
#include <complex>
#include <glm/geometric.hpp>
#include <numbers>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {
namespace {

// Points this close to either end of the chain are left out: the base is cut by the mask and
// the tip is narrower than the tilt needs.
constexpr float kEndMargin = 0.05f;
// A line needs this many read points spread over this much of the blade's length.
constexpr int kMinTwistPoints = 24;
constexpr float kMinTwistSpread = 0.4f;
// Residuals beyond this many RMS (and at least kMinOutlier_rad) are a flying pixel's or a
// neighbour's depth; the line is fitted again without them.
constexpr float kOutlierRms = 3.f;
constexpr float kMinOutlier_rad = 0.17f;
// A twist smaller than this many standard errors of the slope is noise, not a twist.
constexpr float kSignificantSlope = 2.f;
// Reads that, outliers left out, agree less than this about their line (the mean resultant of
// their doubled residuals, about exp(-2 rms^2): 0.85 is a scatter of 0.29 rad rms) hold no face
// direction: not measured, and the widths not scaled. Narrow leaves read by a noisy sensor
// scatter more; scaled by their reads, their widths come out too wide
// (docs/measurements/plant_benchmark.md, width error).
constexpr float kMinAgreement = 0.85f;
// Below this share of its width facing the camera a blade is read too edge-on for its width to
// be scaled back up: the correction stops at 1 / kMinFacing.
constexpr float kMinFacing = 0.35f;

struct Line {
    double intercept = 0.0, slope = 0.0, rms = 0.0, slopeError = 0.0;
    int points = 0;
};

Line fitLine(const std::vector<float>& x, const std::vector<float>& y,
             const std::vector<char>& use) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (std::size_t j = 0; j < x.size(); ++j)
        if (use[j]) sx += x[j], sy += y[j], sxx += x[j] * x[j], sxy += x[j] * y[j], ++m;
    Line l;
    l.points = m;
    const double det = m * sxx - sx * sx;
    if (m < 2 || !(det > 1e-12)) return l;
    l.slope = (m * sxy - sx * sy) / det;
    l.intercept = (sy - l.slope * sx) / m;
    double ss = 0;
    for (std::size_t j = 0; j < x.size(); ++j)
        if (use[j]) ss += std::pow(y[j] - (l.intercept + l.slope * x[j]), 2);
    l.rms = std::sqrt(ss / m);
    // sum (x - mean)^2 = det / m
    l.slopeError = m > 2 ? std::sqrt(ss / (m - 2) / (det / m)) : 0.0;
    return l;
}

// A ribbon's width direction is a line, not an arrow: its angle is known up to a half turn, and
// each read lies in [-pi/2, pi/2]. A blade near edge-on reads on both sides of +-pi/2, and one
// twisted past a quarter turn wraps. So the line through the reads is found on the circle first,
// with the angles doubled (a half turn becomes a whole one): the slope, searched over what a
// library holds, whose residuals agree best (the largest mean resultant of exp(2i(angle - slope
// s))). Each read is then moved by whole half turns to lie nearest that line.
void unwrapAboutCircularLine(std::vector<float>& angle, const std::vector<float>& s,
                             const std::vector<char>& use) {
    // The peak spans radians (the reads spread over at least 0.4 of the blade): a coarse search,
    // then a fine one about its best. Each read's phasor turns by a fixed step from one slope to
    // the next: one complex product per read and slope.
    constexpr double kCoarseStep_rad = 0.1, kFineStep_rad = 0.005;
    std::vector<std::complex<double>> read;
    std::vector<double> along;
    for (std::size_t j = 0; j < angle.size(); ++j)
        if (use[j]) read.push_back(std::polar(1.0, 2.0 * angle[j])), along.push_back(s[j]);
    if (read.empty()) return;
    double bestSlope = 0.0, bestLength = -1.0;
    std::complex<double> bestSum = 0.0;
    const auto search = [&](double from, double step, int steps) {
        std::vector<std::complex<double>> phasor(read.size()), turn(read.size());
        for (std::size_t j = 0; j < read.size(); ++j) {
            phasor[j] = read[j] * std::polar(1.0, -2.0 * from * along[j]);
            turn[j] = std::polar(1.0, -2.0 * step * along[j]);
        }
        for (int k = 0; k <= steps; ++k) {
            std::complex<double> sum = 0.0;
            for (std::size_t j = 0; j < read.size(); ++j) sum += phasor[j], phasor[j] *= turn[j];
            if (std::abs(sum) > bestLength)
                bestLength = std::abs(sum), bestSum = sum, bestSlope = from + k * step;
        }
    };
    const double most = kMaxTwistAtTip_rad;
    search(-most, kCoarseStep_rad, static_cast<int>(2.0 * most / kCoarseStep_rad));
    const double lo = std::max(-most, bestSlope - kCoarseStep_rad);
    const double hi = std::min(most, bestSlope + kCoarseStep_rad);
    search(lo, kFineStep_rad, static_cast<int>((hi - lo) / kFineStep_rad));
    const double intercept = 0.5 * std::arg(bestSum);
    const double halfTurn = std::numbers::pi;
    for (std::size_t j = 0; j < angle.size(); ++j)
        if (use[j]) {
            const double onLine = intercept + bestSlope * s[j];
            angle[j] += static_cast<float>(halfTurn * std::round((onLine - angle[j]) / halfTurn));
        }
}

// How well the reads kept agree about the line: the mean resultant of their doubled residuals
// (1: all on it, near 0: scattered as noise).
float agreementAbout(const Line& line, const std::vector<float>& angle, const std::vector<float>& s,
                     const std::vector<char>& use) {
    std::complex<double> sum = 0.0;
    for (std::size_t j = 0; j < angle.size(); ++j)
        if (use[j]) sum += std::polar(1.0, 2.0 * (angle[j] - line.intercept - line.slope * s[j]));
    return line.points > 0 ? static_cast<float>(std::abs(sum) / line.points) : 0.f;
}

// The same line of the ribbon, its angle moved by whole half turns into [-pi/2, pi/2).
float withinAHalfTurn(double angle) {
    const double halfTurn = std::numbers::pi;
    return static_cast<float>(angle - halfTurn * std::floor(angle / halfTurn + 0.5));
}

// Width direction of the ribbon at a spine point (blade_mesh.h): W = normalize(T x Z).
glm::vec3 widthDirection(const glm::vec3& tangent) {
    const glm::vec3 w = glm::cross(tangent, glm::vec3(0.f, 0.f, 1.f));
    return glm::length(w) > 1e-6f ? glm::normalize(w) : glm::vec3(1.f, 0.f, 0.f);
}

}  // namespace

TwistFit fitTwist(const Skeleton& skeleton, const BladeFrame& frame,
                  const QuadraticBezier& localSpine, const std::vector<float>& t,
                  const std::vector<float>& s) {
    const std::size_t n = skeleton.points_m.size();
    TwistFit out;
    out.facing.assign(n, 1.f);
    if (skeleton.acrossStep_m.size() != n || t.size() != n || s.size() != n) return out;

    std::vector<float> angle(n, 0.f);
    std::vector<char> use(n, 0);
    std::vector<glm::vec3> tangent(n), width(n);
    for (std::size_t j = 0; j < n; ++j) {
        tangent[j] = glm::normalize(localSpine.tangent(t[j]));
        width[j] = widthDirection(tangent[j]);
        const glm::vec3 step = skeleton.acrossStep_m[j];
        const bool onAddedPiece = static_cast<int>(j) < skeleton.rootPoints ||
                                  static_cast<int>(n - j) <= skeleton.tipPoints;
        if (step == glm::vec3(0.f) || onAddedPiece || s[j] < kEndMargin || s[j] > 1.f - kEndMargin)
            continue;
        glm::vec3 a = frame.localFromCamera * step;
        if (glm::dot(a, width[j]) < 0.f) a = -a;  // the across step's side is the contour's
        // Angle about T from W toward T x W: the sense in which blade_mesh.h turns W.
        angle[j] = std::atan2(glm::dot(a, glm::cross(tangent[j], width[j])), glm::dot(a, width[j]));
        use[j] = 1;
    }
    float lo = 1.f, hi = 0.f;
    int reads = 0;
    for (std::size_t j = 0; j < n; ++j)
        if (use[j]) lo = std::min(lo, s[j]), hi = std::max(hi, s[j]), ++reads;
    if (reads < kMinTwistPoints || hi - lo < kMinTwistSpread) return out;
    unwrapAboutCircularLine(angle, s, use);
    Line line = fitLine(s, angle, use);
    const double cut = std::max<double>(kOutlierRms * line.rms, kMinOutlier_rad);
    for (std::size_t j = 0; j < n; ++j)
        if (use[j] && std::abs(angle[j] - (line.intercept + line.slope * s[j])) > cut) use[j] = 0;
    line = fitLine(s, angle, use);
    // More than a full turn from base to tip is no leaf's twist: the reads are noise.
    if (line.points < kMinTwistPoints || std::abs(line.slope) > kMaxTwistAtTip_rad ||
        agreementAbout(line, angle, s, use) < kMinAgreement)
        return out;

    out.measured = true;
    out.points = line.points;
    out.rms_rad = static_cast<float>(line.rms);
    out.baseTilt_rad = withinAHalfTurn(line.intercept);
    const bool significant = std::abs(line.slope) > kSignificantSlope * line.slopeError;
    out.twistAtTip_rad = significant ? static_cast<float>(line.slope) : 0.f;
    // How much of the fitted width direction faces the camera at each point: the width the
    // contour shows is the true width times this.
    const glm::mat3 cameraFromLocal = glm::transpose(frame.localFromCamera);
    for (std::size_t j = 0; j < n; ++j) {
        const float theta = out.baseTilt_rad + out.twistAtTip_rad * s[j];
        const glm::vec3 turned =
            std::cos(theta) * width[j] + std::sin(theta) * glm::cross(tangent[j], width[j]);
        const glm::vec3 w = cameraFromLocal * turned;
        const glm::vec3 ray = glm::normalize(skeleton.points_m[j]);
        out.facing[j] = std::max(kMinFacing, glm::length(w - glm::dot(w, ray) * ray));
    }
    return out;
}

}  // namespace meadow::modeling
