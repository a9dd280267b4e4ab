#include "meadow/synth/scanned_plant.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <tuple>
#include <unordered_set>

#include "meadow/synth/error.h"
#include "plant_organs.h"
#include "plant_points_io.h"

namespace meadow::synth {
namespace {

// A plant spans at least a centimetre and at most a few metres: anything else is another unit.
constexpr float kMinPlantExtent_m = 0.01f;
constexpr float kMaxPlantExtent_m = 5.f;
// Organs touch within this many point spacings, and at least kMinContact_m: on the six
// Label3DMaize shoots this picks the organ their authors labelled first, the stalk, every time.
constexpr float kContactSpacings = 2.f;
constexpr float kMinContact_m = 0.006f;

float segmentDistance(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
    const glm::vec3 ab = b - a;
    const float l2 = glm::dot(ab, ab);
    const float t = l2 > 0.f ? std::clamp(glm::dot(p - a, ab) / l2, 0.f, 1.f) : 0.f;
    return glm::distance(p, a + t * ab);
}

// Each point takes the organ of its nearest skeleton edge (an edge between two organs belongs to
// the one that is not the stem: it is where a leaf leaves it).
std::vector<int> labelsFromSkeleton(const std::vector<glm::vec3>& points,
                                    const plant::SkeletonGraph& g) {
    std::vector<int> labels(points.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
        float best = std::numeric_limits<float>::max();
        for (const auto& [a, b] : g.edges) {
            const float d = segmentDistance(points[i], g.nodes[static_cast<std::size_t>(a)],
                                            g.nodes[static_cast<std::size_t>(b)]);
            if (d < best)
                best = d, labels[i] = std::max(g.organ[static_cast<std::size_t>(a)],
                                               g.organ[static_cast<std::size_t>(b)]);
        }
    }
    return labels;
}

// A leaf's skeleton nodes in order, from the one nearest the stem along the graph's edges.
std::vector<glm::vec3> leafNodesInOrder(const plant::SkeletonGraph& g, int organ) {
    std::vector<std::size_t> nodes;
    for (std::size_t i = 0; i < g.nodes.size(); ++i)
        if (g.organ[i] == organ) nodes.push_back(i);
    if (nodes.empty()) return {};
    std::size_t start = nodes.front();
    float nearest = std::numeric_limits<float>::max();
    for (std::size_t i : nodes)
        for (std::size_t s = 0; s < g.nodes.size(); ++s)
            if (g.organ[s] == 0 && glm::distance(g.nodes[i], g.nodes[s]) < nearest)
                nearest = glm::distance(g.nodes[i], g.nodes[s]), start = i;
    std::vector<glm::vec3> line = {g.nodes[start]};
    std::unordered_set<std::size_t> seen = {start};
    for (std::size_t at = start;;) {
        std::size_t next = at;
        for (const auto& [a, b] : g.edges) {
            const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
            const std::size_t other = ua == at ? ub : ub == at ? ua : at;
            if (other != at && g.organ[other] == organ && !seen.count(other)) next = other;
        }
        if (next == at) break;
        seen.insert(next);
        line.push_back(g.nodes[next]);
        at = next;
    }
    return line;
}

// One point per (cube of side voxel_m, organ): PCL's VoxelGrid would average the labels too.
void thin(std::vector<glm::vec3>& points, std::vector<int>& labels, float voxel_m) {
    std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>, std::size_t> kept;
    std::vector<glm::vec3> p;
    std::vector<int> l;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto key = std::make_tuple(
            static_cast<std::int64_t>(std::floor(points[i].x / voxel_m)),
            static_cast<std::int64_t>(std::floor(points[i].y / voxel_m)),
            static_cast<std::int64_t>(std::floor(points[i].z / voxel_m)), labels[i]);
        if (kept.emplace(key, p.size()).second) p.push_back(points[i]), l.push_back(labels[i]);
    }
    points = std::move(p);
    labels = std::move(l);
}

// Rotation taking `up` to +Y (columns: the world axes in scan coordinates).
glm::mat3 worldFromScan(glm::vec3 up) {
    const glm::vec3 helper =
        std::abs(up.z) < 0.9f ? glm::vec3(0.f, 0.f, 1.f) : glm::vec3(1.f, 0.f, 0.f);
    const glm::vec3 x = glm::normalize(glm::cross(up, helper));
    const glm::vec3 z = glm::cross(x, up);
    return glm::transpose(glm::mat3(x, up, z));
}

}  // namespace

float metresPer(LengthUnit unit) {
    switch (unit) {
        case LengthUnit::Millimetre:
            return 0.001f;
        case LengthUnit::Centimetre:
            return 0.01f;
        case LengthUnit::Metre:
            return 1.f;
    }
    return 1.f;
}

const PlantOrgan* ScannedPlant::organ(int label) const {
    for (const PlantOrgan& o : organs)
        if (o.label == label) return &o;
    return nullptr;
}

const PlantOrgan& ScannedPlant::stem() const { return *organ(stemLabel); }

float ScannedPlant::height_m() const {
    float top = 0.f;
    for (const glm::vec3& p : points_m) top = std::max(top, p.y);
    return top;
}

ScannedPlant loadScannedPlant(const std::filesystem::path& file,
                              const ScannedPlantOptions& options) {
    plant::LabelledPoints read = plant::readLabelledPoints(file);
    std::optional<plant::SkeletonGraph> graph;
    if (!options.skeleton.empty()) graph = plant::readSkeletonGraph(options.skeleton);
    if (read.labels.empty()) {
        if (!graph)
            throw SynthError(file.string() +
                             ": its points carry no organ labels; give the plant's skeleton graph "
                             "(--plant-skeleton) to label them");
        read.labels = labelsFromSkeleton(read.points, *graph);
    }
    const float scale = metresPer(options.unit);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (glm::vec3& p : read.points) {
        p *= scale;
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const std::string unit(kLengthUnitNames.name(options.unit));
    if (!(extent >= kMinPlantExtent_m && extent <= kMaxPlantExtent_m))
        throw SynthError(file.string() + ": the plant spans " + std::to_string(extent) + " m in " +
                         unit +
                         ", not the 0.01-5 m of a plant; give its unit "
                         "(--plant-unit mm, cm or m)");
    if (options.voxel_m > 0.f) thin(read.points, read.labels, options.voxel_m);
    if (graph)
        for (glm::vec3& n : graph->nodes) n *= scale;

    std::vector<plant::OrganPoints> organs = plant::groupByOrgan(read.points, read.labels);
    if (organs.size() < 2)
        throw SynthError(file.string() + ": holds " + std::to_string(organs.size()) +
                         " organ label(s); a plant needs its stem and at least one leaf");
    const float spacing = plant::pointSpacing_m(read.points);
    ScannedPlant plant;
    plant.name = file.stem().string();
    if (graph) {
        plant.stemLabel = 0;
        plant.stemFoundBy = "organ 0 of the skeleton graph " + options.skeleton.filename().string();
    } else {
        const plant::StemChoice stem =
            plant::findStem(organs, std::max(kContactSpacings * spacing, kMinContact_m));
        plant.stemLabel = stem.label;
        plant.stemFoundBy = stem.reason;
    }
    const auto stemIt =
        std::find_if(organs.begin(), organs.end(),
                     [&](const plant::OrganPoints& o) { return o.label == plant.stemLabel; });
    if (stemIt == organs.end() || stemIt->points.size() < 3)
        throw SynthError(file.string() + ": the stem (organ " + std::to_string(plant.stemLabel) +
                         ") has fewer than 3 points");
    const plant::StemAxis axis = plant::stemAxis(stemIt->points, read.points);

    // World: +Y up the stem, its foot at the origin.
    const glm::mat3 rotation = worldFromScan(axis.up);
    const auto toWorld = [&](glm::vec3 p) { return rotation * (p - axis.foot); };
    for (glm::vec3& p : read.points) p = toWorld(p);
    for (plant::OrganPoints& o : organs)
        for (glm::vec3& p : o.points) p = toWorld(p);
    const plant::StemAxis worldAxis{{0.f, 1.f, 0.f}, {0.f, 0.f, 0.f}};
    const std::vector<glm::vec3>& stemPoints = stemIt->points;
    for (const plant::OrganPoints& o : organs) {
        PlantOrgan organ;
        organ.label = o.label;
        organ.stem = o.label == plant.stemLabel;
        organ.points = o.points.size();
        plant::CentreLine line;
        if (organ.stem) {
            line = plant::stemCentreLine(o.points, worldAxis);
        } else if (graph) {
            std::vector<glm::vec3> nodes = leafNodesInOrder(*graph, o.label);
            for (glm::vec3& n : nodes) n = toWorld(n);
            line = plant::leafAlongLine(o.points, std::move(nodes));
        } else {
            line = plant::leafCentreLine(o.points, stemPoints, spacing);
        }
        organ.centreLine_m = std::move(line.line);
        organ.length_m = line.length_m;
        organ.maxWidth_m = line.maxWidth_m;
        plant.organs.push_back(std::move(organ));
    }
    plant.points_m = std::move(read.points);
    plant.labels = std::move(read.labels);
    return plant;
}

}  // namespace meadow::synth
