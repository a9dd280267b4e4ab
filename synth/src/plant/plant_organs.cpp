#include "plant_organs.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <queue>
#include <unordered_map>

namespace meadow::synth::plant {
namespace {

// Neighbours per point in the leaf's graph: enough to bridge the scan's gaps, few enough that an
// edge does not jump across a fold of the leaf.
constexpr int kGraphNeighbours = 8;
// The sheath: the first tenth of a leaf's length wraps the stem and is not its blade's width.
constexpr float kSheathFraction = 0.1f;
// The 5-95 % spread of points spread evenly across a width is 0.9 of it: the width is the spread
// over this (a quantile range, not the extremes, so a stray point does not widen the leaf).
constexpr float kEvenSpreadShare = 0.9f;
// A bin needs this many points for its spread to be a width.
// Smoothing passes over a leaf's centre line: one per this many vertices.
constexpr std::size_t kVerticesPerSmoothingPass = 10;
constexpr std::size_t kMinBinPoints = 8;

pcl::PointCloud<pcl::PointXYZ>::Ptr cloudOf(const std::vector<glm::vec3>& points) {
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud->reserve(points.size());
    for (const glm::vec3& p : points) cloud->emplace_back(p.x, p.y, p.z);
    return cloud;
}

struct Pca {
    glm::vec3 mean{0.f};
    glm::vec3 axis[3];  // by decreasing variance
    float variance[3] = {0.f, 0.f, 0.f};
};
Pca pca(const std::vector<glm::vec3>& points) {
    Pca out;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const glm::vec3& p : points) mean += Eigen::Vector3d(p.x, p.y, p.z);
    mean /= static_cast<double>(std::max<std::size_t>(points.size(), 1));
    Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
    for (const glm::vec3& p : points) {
        const Eigen::Vector3d d = Eigen::Vector3d(p.x, p.y, p.z) - mean;
        c += d * d.transpose();
    }
    c /= static_cast<double>(std::max<std::size_t>(points.size(), 1));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(c);
    out.mean = glm::vec3(mean.x(), mean.y(), mean.z());
    for (int k = 0; k < 3; ++k) {  // Eigen sorts increasing
        const Eigen::Vector3d v = solver.eigenvectors().col(2 - k);
        out.axis[k] = glm::vec3(v.x(), v.y(), v.z());
        out.variance[k] = static_cast<float>(solver.eigenvalues()(2 - k));
    }
    return out;
}

// Cells of side `cell` holding each organ's points, to test contacts without all pairs.
struct CellKey {
    std::int64_t x, y, z;
    bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
    std::size_t operator()(const CellKey& k) const {
        return static_cast<std::size_t>(k.x * 73856093 ^ k.y * 19349663 ^ k.z * 83492791);
    }
};

float quantile(std::vector<float> v, float q) {
    if (v.empty()) return 0.f;
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<float>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
}

float polylineLength(const std::vector<glm::vec3>& line) {
    float length = 0.f;
    for (std::size_t i = 1; i < line.size(); ++i) length += glm::distance(line[i - 1], line[i]);
    return length;
}

// Arc length along `line` of the point on it nearest p.
float arcLengthOf(const std::vector<glm::vec3>& line, const std::vector<float>& cumulative,
                  glm::vec3 p) {
    float best = std::numeric_limits<float>::max(), at = 0.f;
    for (std::size_t i = 1; i < line.size(); ++i) {
        const glm::vec3 a = line[i - 1], ab = line[i] - a;
        const float l2 = glm::dot(ab, ab);
        const float t = l2 > 0.f ? std::clamp(glm::dot(p - a, ab) / l2, 0.f, 1.f) : 0.f;
        const float d = glm::distance(p, a + t * ab);
        if (d < best) best = d, at = cumulative[i - 1] + t * std::sqrt(l2);
    }
    return at;
}

// The widest 5-95 % spread of the leaf's points across the line, per bin of arc length, beyond
// the sheath.
float maxWidthAlong(const std::vector<glm::vec3>& leaf, const std::vector<glm::vec3>& line) {
    if (line.size() < 2) return 0.f;
    std::vector<float> cumulative(line.size(), 0.f);
    for (std::size_t i = 1; i < line.size(); ++i)
        cumulative[i] = cumulative[i - 1] + glm::distance(line[i - 1], line[i]);
    const float length = cumulative.back();
    if (!(length > 0.f)) return 0.f;
    const int bins = static_cast<int>(line.size()) - 1;
    std::vector<std::vector<glm::vec3>> members(static_cast<std::size_t>(bins));
    for (const glm::vec3& p : leaf) {
        const float s = arcLengthOf(line, cumulative, p);
        const auto b =
            std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin();
        members[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(b - 1, 0, bins - 1))].push_back(
            p);
    }
    float widest = 0.f;
    for (int b = 0; b < bins; ++b) {
        if (cumulative[static_cast<std::size_t>(b)] < kSheathFraction * length ||
            members[static_cast<std::size_t>(b)].size() < kMinBinPoints)
            continue;
        const glm::vec3 t = glm::normalize(line[static_cast<std::size_t>(b) + 1] -
                                           line[static_cast<std::size_t>(b)]);
        std::vector<glm::vec3> across;
        for (const glm::vec3& p : members[static_cast<std::size_t>(b)])
            across.push_back(p - glm::dot(p, t) * t);
        const Pca spread = pca(across);
        std::vector<float> along;
        for (const glm::vec3& p : across)
            along.push_back(glm::dot(p - spread.mean, spread.axis[0]));
        widest =
            std::max(widest, (quantile(along, 0.95f) - quantile(along, 0.05f)) / kEvenSpreadShare);
    }
    return widest;
}

}  // namespace

std::vector<OrganPoints> groupByOrgan(const std::vector<glm::vec3>& points,
                                      const std::vector<int>& labels) {
    std::map<int, std::vector<glm::vec3>> byLabel;
    for (std::size_t i = 0; i < points.size(); ++i) byLabel[labels[i]].push_back(points[i]);
    std::vector<OrganPoints> out;
    for (auto& [label, p] : byLabel) out.push_back({label, std::move(p)});
    return out;
}

float pointSpacing_m(const std::vector<glm::vec3>& points) {
    if (points.size() < 2) return 0.f;
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud(cloudOf(points));
    std::vector<float> nearest;
    std::vector<int> index(2);
    std::vector<float> d2(2);
    // Every point of a small scan, a regular sample of a large one: the median needs no more.
    const std::size_t step = std::max<std::size_t>(1, points.size() / 20000);
    for (std::size_t i = 0; i < points.size(); i += step)
        if (tree.nearestKSearch(pcl::PointXYZ(points[i].x, points[i].y, points[i].z), 2, index,
                                d2) == 2)
            nearest.push_back(std::sqrt(d2[1]));
    return quantile(nearest, 0.5f);
}

StemChoice findStem(const std::vector<OrganPoints>& organs, float contact_m) {
    // Points by cell of side contact_m: two points within contact_m lie in the same or
    // neighbouring cells.
    struct Member {
        std::size_t organ;
        glm::vec3 point;
    };
    std::unordered_map<CellKey, std::vector<Member>, CellHash> cells;
    const auto cellOf = [contact_m](glm::vec3 p) {
        return CellKey{static_cast<std::int64_t>(std::floor(p.x / contact_m)),
                       static_cast<std::int64_t>(std::floor(p.y / contact_m)),
                       static_cast<std::int64_t>(std::floor(p.z / contact_m))};
    };
    for (std::size_t o = 0; o < organs.size(); ++o)
        for (const glm::vec3& p : organs[o].points) cells[cellOf(p)].push_back({o, p});
    std::vector<std::vector<char>> touches(organs.size(), std::vector<char>(organs.size(), 0));
    for (const auto& [key, members] : cells)
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = cells.find({key.x + dx, key.y + dy, key.z + dz});
                    if (it == cells.end()) continue;
                    for (const Member& a : members)
                        for (const Member& b : it->second)
                            if (a.organ != b.organ && !touches[a.organ][b.organ] &&
                                glm::distance(a.point, b.point) < contact_m)
                                touches[a.organ][b.organ] = touches[b.organ][a.organ] = 1;
                }
    StemChoice best;
    int bestContacts = -1;
    float bestElongation = -1.f;
    for (std::size_t o = 0; o < organs.size(); ++o) {
        const int contacts = static_cast<int>(std::count(touches[o].begin(), touches[o].end(), 1));
        const Pca shape = pca(organs[o].points);
        const float elongation =
            shape.variance[1] > 0.f ? std::sqrt(shape.variance[0] / shape.variance[1]) : 0.f;
        if (contacts > bestContacts || (contacts == bestContacts && elongation > bestElongation)) {
            best.label = organs[o].label;
            bestContacts = contacts;
            bestElongation = elongation;
        }
    }
    char elongated[16];
    std::snprintf(elongated, sizeof elongated, "%.1f", bestElongation);
    best.reason = "organ " + std::to_string(best.label) + ": it touches " +
                  std::to_string(bestContacts) + " of the " + std::to_string(organs.size() - 1) +
                  " other organs within " +
                  std::to_string(static_cast<int>(contact_m * 1000.f + 0.5f)) +
                  " mm, the most (leaves leave the stem), and is the most elongated of those that "
                  "touch as many (" +
                  elongated + " times longer than wide)";
    return best;
}

StemAxis stemAxis(const std::vector<glm::vec3>& stem, const std::vector<glm::vec3>& all) {
    const Pca shape = pca(stem);
    glm::vec3 up = glm::normalize(shape.axis[0]);
    double stemMean = 0.0, allMean = 0.0;
    for (const glm::vec3& p : stem) stemMean += glm::dot(p, up);
    for (const glm::vec3& p : all) allMean += glm::dot(p, up);
    if (allMean / static_cast<double>(all.size()) < stemMean / static_cast<double>(stem.size()))
        up = -up;
    std::vector<float> heights;
    for (const glm::vec3& p : stem) heights.push_back(glm::dot(p - shape.mean, up));
    const float lowest = quantile(heights, 0.01f);
    return {up, shape.mean + lowest * up};
}

CentreLine leafCentreLine(const std::vector<glm::vec3>& leaf, const std::vector<glm::vec3>& stem,
                          float spacing_m) {
    CentreLine out;
    if (leaf.size() < 3 || stem.empty()) return out;
    // Base: the leaf's point nearest the stem.
    pcl::KdTreeFLANN<pcl::PointXYZ> stemTree;
    stemTree.setInputCloud(cloudOf(stem));
    std::vector<int> index(1);
    std::vector<float> d2(1);
    std::size_t base = 0;
    float nearest = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < leaf.size(); ++i)
        if (stemTree.nearestKSearch(pcl::PointXYZ(leaf[i].x, leaf[i].y, leaf[i].z), 1, index, d2) ==
                1 &&
            d2[0] < nearest)
            nearest = d2[0], base = i;

    // Shortest paths over the nearest-neighbour graph (Dijkstra).
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    const auto cloud = cloudOf(leaf);
    tree.setInputCloud(cloud);
    const int k = std::min<int>(kGraphNeighbours + 1, static_cast<int>(leaf.size()));
    std::vector<std::vector<std::pair<std::size_t, float>>> edges(leaf.size());
    std::vector<int> nn(static_cast<std::size_t>(k));
    std::vector<float> nd2(static_cast<std::size_t>(k));
    for (std::size_t i = 0; i < leaf.size(); ++i) {
        const int found = tree.nearestKSearch((*cloud)[i], k, nn, nd2);
        for (int j = 1; j < found; ++j) {
            const auto other = static_cast<std::size_t>(nn[static_cast<std::size_t>(j)]);
            const float d = std::sqrt(nd2[static_cast<std::size_t>(j)]);
            edges[i].emplace_back(other, d);
            edges[other].emplace_back(i, d);
        }
    }
    std::vector<float> g(leaf.size(), std::numeric_limits<float>::infinity());
    using Item = std::pair<float, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    g[base] = 0.f;
    queue.emplace(0.f, base);
    while (!queue.empty()) {
        const auto [d, i] = queue.top();
        queue.pop();
        if (d > g[i]) continue;
        for (const auto& [j, w] : edges[i])
            if (d + w < g[j]) g[j] = d + w, queue.emplace(g[j], j);
    }
    float reach = 0.f;
    for (float d : g)
        if (std::isfinite(d)) reach = std::max(reach, d);
    if (!(reach > 0.f)) return out;
    // Bins a few point spacings long, at least 40 along a leaf.
    const int bins = std::clamp(static_cast<int>(reach / (3.f * spacing_m)), 8, 200);
    std::vector<glm::vec3> sum(static_cast<std::size_t>(bins), glm::vec3(0.f));
    std::vector<int> count(static_cast<std::size_t>(bins), 0);
    for (std::size_t i = 0; i < leaf.size(); ++i) {
        if (!std::isfinite(g[i])) continue;
        const int b = std::min(bins - 1, static_cast<int>(g[i] / reach * static_cast<float>(bins)));
        sum[static_cast<std::size_t>(b)] += leaf[i];
        ++count[static_cast<std::size_t>(b)];
    }
    out.line.push_back(leaf[base]);
    for (int b = 0; b < bins; ++b)
        if (count[static_cast<std::size_t>(b)] > 0)
            out.line.push_back(sum[static_cast<std::size_t>(b)] /
                               static_cast<float>(count[static_cast<std::size_t>(b)]));
    // Each centroid carries the scan's noise across the leaf; a zigzag through them would add to
    // the length. A [1 2 1] / 4 pass per ten vertices smooths it, the ends held.
    for (std::size_t pass = 0; pass < out.line.size() / kVerticesPerSmoothingPass; ++pass) {
        std::vector<glm::vec3> next = out.line;
        for (std::size_t i = 1; i + 1 < out.line.size(); ++i)
            next[i] = 0.25f * out.line[i - 1] + 0.5f * out.line[i] + 0.25f * out.line[i + 1];
        out.line = std::move(next);
    }
    out.length_m = polylineLength(out.line);
    out.maxWidth_m = maxWidthAlong(leaf, out.line);
    return out;
}

CentreLine leafAlongLine(const std::vector<glm::vec3>& leaf, std::vector<glm::vec3> line) {
    CentreLine out;
    out.line = std::move(line);
    out.length_m = polylineLength(out.line);
    out.maxWidth_m = maxWidthAlong(leaf, out.line);
    return out;
}

CentreLine stemCentreLine(const std::vector<glm::vec3>& stem, const StemAxis& axis) {
    CentreLine out;
    std::vector<float> heights, radial;
    for (const glm::vec3& p : stem) {
        const float h = glm::dot(p - axis.foot, axis.up);
        heights.push_back(h);
        radial.push_back(glm::length(p - axis.foot - h * axis.up));
    }
    const float top = quantile(heights, 0.99f);
    out.line = {axis.foot, axis.foot + top * axis.up};
    out.length_m = top;
    out.maxWidth_m = 2.f * quantile(radial, 0.5f);
    return out;
}

}  // namespace meadow::synth::plant
