// GCC 12 takes the SSE loads of Eigen's SVD in PCL's ICP (Umeyama), inlined here, for reads out of
// bounds: a false positive in Eigen's code, which it places in the intrinsics' header, so the
// warning is off for the whole file.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include "meadow/capture/view_registration.h"

#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/elch.h>
#include <pcl/registration/icp.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "meadow/capture/error.h"

namespace meadow::capture {

namespace {

constexpr float kMillimetresPerMetre = 1000.f;
// The readings this low along up (a share of the cloud's height) are the plant's foot, which a
// turntable turns about.
constexpr float kFootShare = 0.1f;
constexpr int kIcpIterations = 20;

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr toCloud(const std::vector<glm::vec3>& points) {
    auto cloud = std::make_shared<Cloud>();
    cloud->reserve(points.size());
    for (const glm::vec3& p : points) cloud->push_back({p.x, p.y, p.z});
    return cloud;
}

// The mean of the readings lowest along `up`: where the plant stands.
glm::vec3 footOf(const std::vector<glm::vec3>& points, const glm::vec3& up) {
    std::vector<float> heights;
    heights.reserve(points.size());
    for (const glm::vec3& p : points) heights.push_back(glm::dot(p, up));
    const auto [low, high] = std::minmax_element(heights.begin(), heights.end());
    const float limit = *low + kFootShare * (*high - *low);
    glm::vec3 sum{0.f};
    int n = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (heights[i] <= limit) sum += points[i], ++n;
    return sum / static_cast<float>(std::max(n, 1));
}

// A turn of `angle_deg` about the axis along `up` through `pivot`.
glm::mat4 turnAbout(const glm::vec3& pivot, const glm::vec3& up, float angle_deg) {
    return glm::translate(glm::mat4(1.f), pivot) *
           glm::rotate(glm::mat4(1.f), glm::radians(angle_deg), up) *
           glm::translate(glm::mat4(1.f), -pivot);
}

Eigen::Matrix4f toEigen(const glm::mat4& m) {
    Eigen::Matrix4f e;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) e(r, c) = m[c][r];
    return e;
}

glm::mat4 toGlm(const Eigen::Matrix4f& e) {
    glm::mat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = e(r, c);
    return m;
}

// The turn a rigid motion makes about `up` (degrees): the angle its rotation takes a direction
// across `up` through, seen along `up`.
float turnAngle_deg(const glm::mat4& motion, const glm::vec3& up) {
    glm::vec3 across = glm::cross(up, glm::vec3(1.f, 0.f, 0.f));
    if (glm::length(across) < 0.1f) across = glm::cross(up, glm::vec3(0.f, 0.f, 1.f));
    across = glm::normalize(across);
    glm::vec3 turned = glm::vec3(motion * glm::vec4(across, 0.f));
    turned -= glm::dot(turned, up) * up;
    const float angle =
        std::atan2(glm::dot(glm::cross(across, turned), up), glm::dot(across, turned));
    return glm::degrees(angle);
}

struct PairFit {
    glm::mat4 targetFromSource{1.f};
    float inlierShare = 0.f;
};

// The share of `source`, every `stride`-th reading, that lies within params.inlierDistance_m of
// the target once moved by `motion`.
float lyingOn(const Cloud& source, const glm::mat4& motion,
              const pcl::KdTreeFLANN<pcl::PointXYZ>& targetTree,
              const ViewRegistrationParams& params, std::size_t stride = 1) {
    std::vector<int> index(1);
    std::vector<float> squared(1);
    const float inlier2 = params.inlierDistance_m * params.inlierDistance_m;
    int inliers = 0, tried = 0;
    for (std::size_t i = 0; i < source.size(); i += stride, ++tried) {
        const glm::vec3 p =
            glm::vec3(motion * glm::vec4(source[i].x, source[i].y, source[i].z, 1.f));
        if (targetTree.nearestKSearch(pcl::PointXYZ(p.x, p.y, p.z), 1, index, squared) < 1)
            continue;
        if (squared[0] <= inlier2) ++inliers;
    }
    return tried ? static_cast<float>(inliers) / static_cast<float>(tried) : 0.f;
}

// The source thinned evenly to at most params.maxPoints readings; the target is taken whole, so
// that a reading of the source that lies on the plant finds one of the target's within the
// sensor's own spacing.
Cloud::Ptr thinnedSource(const ViewCloud& source, const ViewRegistrationParams& params) {
    const std::size_t thinning = std::max<std::size_t>(
        1, (source.points_m.size() + params.maxPoints - 1) / params.maxPoints);
    std::vector<glm::vec3> thinned;
    for (std::size_t i = 0; i < source.points_m.size(); i += thinning)
        thinned.push_back(source.points_m[i]);
    return toCloud(thinned);
}

// The sweep's turn that lays most of the source on the target, refined by ICP. Each search in
// PCL's kd-tree costs an OpenMP region in FLANN, so the sweep is scored on a sample and only the
// best few turns are refined.
PairFit registerPair(const ViewCloud& source, const ViewCloud& target,
                     const ViewRegistrationParams& params) {
    const Cloud::Ptr sourceCloud = thinnedSource(source, params);
    const Cloud::Ptr targetCloud = toCloud(target.points_m);
    pcl::KdTreeFLANN<pcl::PointXYZ> targetTree;
    targetTree.setInputCloud(targetCloud);

    const glm::vec3 up = glm::normalize(target.up);
    const glm::vec3 pivot = footOf(target.points_m, up);
    constexpr std::size_t kSweepSamples = 400;
    const std::size_t stride = std::max<std::size_t>(1, sourceCloud->size() / kSweepSamples);
    std::vector<std::pair<float, glm::mat4>> turns;
    const int steps = static_cast<int>(std::floor(params.sweepRange_deg / params.sweepStep_deg));
    for (int k = -steps; k <= steps; ++k) {
        const glm::mat4 turn = turnAbout(pivot, up, static_cast<float>(k) * params.sweepStep_deg);
        turns.emplace_back(lyingOn(*sourceCloud, turn, targetTree, params, stride), turn);
    }
    // Before ICP a turn near the true one can still score below a wrong one that lays the stem
    // on the stem: the best few are refined.
    constexpr std::size_t kRefined = 3;
    const std::size_t refined = std::min(kRefined, turns.size());
    std::partial_sort(turns.begin(), turns.begin() + static_cast<std::ptrdiff_t>(refined),
                      turns.end(), [](const auto& a, const auto& b) { return a.first > b.first; });

    pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
    icp.setInputTarget(targetCloud);
    icp.setInputSource(sourceCloud);
    icp.setMaxCorrespondenceDistance(params.maxPairing_m);
    icp.setMaximumIterations(kIcpIterations);
    icp.setTransformationEpsilon(1e-8);
    PairFit best;
    best.inlierShare = -1.f;
    for (std::size_t i = 0; i < refined; ++i) {
        Cloud aligned;
        icp.align(aligned, toEigen(turns[i].second));
        PairFit fit;
        fit.targetFromSource = toGlm(icp.getFinalTransformation());
        fit.inlierShare = lyingOn(*sourceCloud, fit.targetFromSource, targetTree, params);
        if (fit.inlierShare > best.inlierShare) best = fit;
    }
    return best;
}

std::string percent(float share) {
    return std::to_string(static_cast<int>(std::lround(share * 100.f))) + " %";
}

// `view` registered to `previous`, placed at `previousPlace`: in its chain, or with why not.
RegisteredView registerToPrevious(const ViewCloud& view, const ViewCloud& previous,
                                  const RegisteredView& previousPlace,
                                  const ViewRegistrationParams& params) {
    constexpr std::size_t kMinPoints = 10;
    RegisteredView r;
    r.frame = view.frame;
    r.chain = previousPlace.chain + 1;  // unless registered below
    if (view.points_m.size() < kMinPoints || previous.points_m.size() < kMinPoints) {
        r.why = "too few plant readings to register (" +
                std::to_string(std::min(view.points_m.size(), previous.points_m.size())) +
                " in one of the two views, " + std::to_string(kMinPoints) + " needed)";
        return r;
    }
    const PairFit fit = registerPair(view, previous, params);
    r.inlierShare = fit.inlierShare;
    r.turn_deg = turnAngle_deg(fit.targetFromSource, glm::normalize(previous.up));
    if (fit.inlierShare < params.minInlierShare) {
        r.why = "only " + percent(fit.inlierShare) + " of its plant readings came to lie on " +
                "frame " + std::to_string(previousPlace.frame) + "'s (" +
                percent(params.minInlierShare) + " needed)";
        return r;
    }
    r.chain = previousPlace.chain;
    r.registeredTo = previousPlace.frame;
    r.chainFromView = previousPlace.chainFromView * fit.targetFromSource;
    return r;
}

}  // namespace

std::string ViewRegistrationParams::problem() const {
    std::ostringstream why;
    if (maxPoints < 10)
        why << "maxPoints " << maxPoints << " is below 10";
    else if (!(sweepStep_deg > 0.f) || !(sweepRange_deg >= 0.f) || sweepRange_deg > 180.f)
        why << "the sweep (" << sweepRange_deg << " deg by " << sweepStep_deg
            << " deg) is not a range within 180 deg and a positive step";
    else if (!(maxPairing_m > 0.f) || !(inlierDistance_m > 0.f))
        why << "pairing and inlier distances must be positive";
    else if (!(minInlierShare >= 0.f && minInlierShare <= 1.f))
        why << "minInlierShare " << minInlierShare << " is not within 0 to 1";
    else if (fallbackViews < 0 || fallbackViews > 8)
        why << "fallbackViews " << fallbackViews << " is not within 0 to 8";
    return why.str();
}

float shareLyingOn(const ViewCloud& source, const ViewCloud& target,
                   const glm::mat4& targetFromSource, const ViewRegistrationParams& params) {
    if (const std::string why = params.problem(); !why.empty())
        throw CaptureError("view registration: " + why);
    if (source.points_m.empty() || target.points_m.empty()) return 0.f;
    pcl::KdTreeFLANN<pcl::PointXYZ> targetTree;
    targetTree.setInputCloud(toCloud(target.points_m));
    return lyingOn(*thinnedSource(source, params), targetFromSource, targetTree, params);
}

ViewCloud plantCloud(const Segmentation& segmentation, const DepthFrame& frame) {
    ViewCloud view;
    view.frame = frame.index;
    if (segmentation.groundPlane) {
        const cv::Vec4f& g = *segmentation.groundPlane;
        view.up = glm::normalize(glm::vec3(g[0], g[1], g[2]));
    }
    const cv::Mat1b& mask = segmentation.clusterMask;
    if (mask.empty() || mask.size() != frame.depth_mm.size()) return view;
    const int nearest_mm =
        static_cast<int>(std::floor(segmentation.tuftNearest_m * kMillimetresPerMetre));
    const int farthest_mm =
        segmentation.tuftFarthest_m > 0.f
            ? static_cast<int>(std::ceil(segmentation.tuftFarthest_m * kMillimetresPerMetre))
            : std::numeric_limits<int>::max();
    std::vector<cv::Point> pixels;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x) {
            const int d = frame.depth_mm(y, x);
            if (mask(y, x) && d > 0 && d >= nearest_mm && d <= farthest_mm)
                pixels.emplace_back(x, y);
        }
    for (const cv::Point p : pixels)
        view.points_m.push_back(frame.intrinsics.backProject(
            static_cast<float>(p.x), static_cast<float>(p.y),
            static_cast<float>(frame.depth_mm(p)) / kMillimetresPerMetre));
    return view;
}

ViewRegistrar::ViewRegistrar(ViewRegistrationParams params) : params_(std::move(params)) {
    if (const std::string why = params_.problem(); !why.empty())
        throw CaptureError("view registration: " + why);
    // PCL reports on the console (ICP finding too few pairs for a view of something else);
    // registration reports through RegisteredView::why.
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
}

const RegisteredView& ViewRegistrar::add(ViewCloud view) {
    RegisteredView r;
    r.frame = view.frame;
    if (placed_.empty()) {
        chains_ = 1;
        firstView_ = view;
    } else {
        // The view before first, then the ones before that, nearest first.
        const std::size_t tries = recent_.size();
        for (std::size_t back = 1; back <= tries; ++back) {
            const ViewCloud& previous = recent_[tries - back];
            const RegisteredView& previousPlace = placed_[placed_.size() - back];
            RegisteredView tried = registerToPrevious(view, previous, previousPlace, params_);
            if (tried.why.empty()) {
                r = std::move(tried);
                break;
            }
            if (back == 1) r = std::move(tried);  // its reason is the one the user reads
        }
        if (!r.why.empty()) r.chain = chains_++;
    }
    placed_.push_back(std::move(r));
    recent_.push_back(std::move(view));
    const auto keep = static_cast<std::size_t>(1 + std::max(0, params_.fallbackViews));
    if (recent_.size() > keep) recent_.erase(recent_.begin());
    return placed_.back();
}

const LoopClosure& ViewRegistrar::closeLoop() {
    if (loop_.lastFrame >= 0 || placed_.size() < 3) return loop_;
    loop_.lastFrame = placed_.back().frame;
    if (placed_.back().chain != placed_.front().chain)
        joinLastChainToFirst();
    else
        spreadLoopDrift();
    return loop_;
}

// What moves the last view from where its chain put it to where its own registration to
// `target`, the first view of a chain (`targetPlace`), puts it; or nothing, with why.
std::optional<glm::mat4> ViewRegistrar::lastOn(const ViewCloud& target,
                                               const RegisteredView& targetPlace) {
    const RegisteredView direct = registerToPrevious(recent_.back(), target, targetPlace, params_);
    if (direct.why.empty())
        return direct.chainFromView * glm::inverse(placed_.back().chainFromView);
    loop_.why = "frame " + std::to_string(loop_.lastFrame) + " not registered to frame " +
                std::to_string(loop_.firstFrame) + ": " + direct.why;
    return std::nullopt;
}

// A turntable's views broken into chains: the last chain ends where the first began, so its last
// view lies on the first view, and the two chains are one.
void ViewRegistrar::joinLastChainToFirst() {
    const RegisteredView& first = placed_.front();
    loop_.firstFrame = first.frame;
    const std::optional<glm::mat4> firstFromLast = lastOn(firstView_, first);
    if (!firstFromLast) return;
    const int last = placed_.back().chain;
    for (RegisteredView& v : placed_)
        if (v.chain == last)
            v.chain = first.chain, v.chainFromView = *firstFromLast * v.chainFromView;
    loop_.joinedChains = true;
}

// One chain round the plant: its last view registered to its first too, and the difference, the
// drift gathered along the chain, spread over the chain's views. The chain is the first one (a
// view that fell back past a broken one may have rejoined it after another chain began).
void ViewRegistrar::spreadLoopDrift() {
    const int chain = placed_.front().chain;
    loop_.firstFrame = placed_.front().frame;
    std::map<int, std::size_t> vertexOf;  // frame -> the chain's views in order
    std::vector<std::size_t> members;     // indices into placed_
    for (std::size_t i = 0; i < placed_.size(); ++i)
        if (placed_[i].chain == chain)
            vertexOf[placed_[i].frame] = members.size(), members.push_back(i);
    for (std::size_t v = members.size() - 1; v != 0;
         v = vertexOf.at(placed_[members[v]].registeredTo))
        loop_.chainTurn_deg += placed_[members[v]].turn_deg;
    // Short of half a turn the last view is no nearer the first one way round than the other.
    if (std::abs(loop_.chainTurn_deg) < 180.f) {
        loop_.why = "the chain from frame " + std::to_string(loop_.firstFrame) + " turned " +
                    std::to_string(static_cast<int>(std::lround(loop_.chainTurn_deg))) +
                    " deg, not round the plant";
        return;
    }
    const std::optional<glm::mat4> found = lastOn(firstView_, placed_.front());
    if (!found) return;
    const glm::mat4& correction = *found;
    double moved = 0.0;
    for (const glm::vec3& p : recent_.back().points_m) {
        const glm::vec4 chained = placed_.back().chainFromView * glm::vec4(p, 1.f);
        moved += glm::distance(glm::vec3(correction * chained), glm::vec3(chained));
    }
    loop_.drift_mm = static_cast<float>(kMillimetresPerMetre * moved /
                                        static_cast<double>(recent_.back().points_m.size()));
    loop_.drift_deg = glm::degrees(glm::angle(glm::quat_cast(glm::mat3(correction))));

    // ELCH spreads the correction along the graph of the chain's registrations, from none at
    // its first view to all of it at its last; a view off that path takes its parent's share.
    using Elch = pcl::registration::ELCH<pcl::PointXYZ>;
    auto graph = std::make_shared<Elch::LoopGraph>();
    for (std::size_t v = 0; v < members.size(); ++v) {
        boost::add_vertex(*graph);
        (*graph)[v].cloud = std::make_shared<Cloud>();  // ELCH moves it; the places are kept here
        if (v > 0) boost::add_edge(v, vertexOf.at(placed_[members[v]].registeredTo), *graph);
    }
    Elch elch;
    elch.setLoopGraph(graph);
    elch.setLoopStart(0);
    elch.setLoopEnd(members.size() - 1);
    elch.setLoopTransform(toEigen(correction));
    elch.compute();
    for (std::size_t v = 0; v < members.size(); ++v)
        placed_[members[v]].chainFromView =
            toGlm((*graph)[v].transform.matrix()) * placed_[members[v]].chainFromView;
    loop_.closed = true;
}

std::vector<RegisteredView> registerViews(const std::vector<ViewCloud>& views,
                                          const ViewRegistrationParams& params) {
    ViewRegistrar registrar(params);
    for (const ViewCloud& view : views) registrar.add(view);
    return registrar.views();
}

}  // namespace meadow::capture

#pragma GCC diagnostic pop
