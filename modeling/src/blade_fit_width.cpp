// Width profile over normalised arc length, least squares on a hat-function basis.
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {
namespace {

// Weight of the second-difference penalty relative to the data term (per measurement). Small:
// it only decides samples that no measurement constrains, and barely smooths the others.
constexpr double kSmoothnessWeight = 1e-3;

}  // namespace

WidthProfile fitWidthProfile(const std::vector<float>& s, const std::vector<float>& width_m,
                             int samples) {
    if (samples < 2)
        throw std::invalid_argument("fitWidthProfile: samples must be >= 2, got " +
                                    std::to_string(samples));
    if (s.empty() || s.size() != width_m.size())
        throw std::invalid_argument(
            "fitWidthProfile: need as many arc fractions as widths, and >= 1, got " +
            std::to_string(s.size()) + " and " + std::to_string(width_m.size()));
    const int n = samples;
    cv::Mat1d normal = cv::Mat1d::zeros(n, n), rhs = cv::Mat1d::zeros(n, 1);
    for (std::size_t j = 0; j < s.size(); ++j) {
        const double x = std::clamp(static_cast<double>(s[j]), 0.0, 1.0) * (n - 1);
        const int i = std::min(static_cast<int>(x), n - 2);
        const double f = x - i;
        const double w[2] = {1.0 - f, f};
        for (int a = 0; a < 2; ++a) {
            rhs(i + a, 0) += w[a] * width_m[j];
            for (int b = 0; b < 2; ++b) normal(i + a, i + b) += w[a] * w[b];
        }
    }
    const double lambda = kSmoothnessWeight * static_cast<double>(s.size()) / n;
    for (int i = 1; i + 1 < n; ++i) {
        const int idx[3] = {i - 1, i, i + 1};
        const double c[3] = {1.0, -2.0, 1.0};
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) normal(idx[a], idx[b]) += lambda * c[a] * c[b];
    }
    // A tiny ridge keeps the system regular when two samples share no measurement at all.
    for (int i = 0; i < n; ++i) normal(i, i) += 1e-12;
    cv::Mat1d solution;
    cv::solve(normal, rhs, solution, cv::DECOMP_SVD);
    WidthProfile profile;
    profile.width_m.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
        profile.width_m[i] = std::max(0.f, static_cast<float>(solution(i, 0)));
    return profile;
}

float widthProfileMae_m(const WidthProfile& profile, const std::vector<float>& s,
                        const std::vector<float>& width_m) {
    if (s.empty()) return 0.f;
    double sum = 0.0;
    for (std::size_t j = 0; j < s.size(); ++j) sum += std::abs(profile.at(s[j]) - width_m[j]);
    return static_cast<float>(sum / static_cast<double>(s.size()));
}

}  // namespace meadow::modeling
