// Finding the plant in a scene (PlantFinding::Clusters): the large planes of the room (floor,
// walls, table tops) are fitted with PCL's RANSAC and removed (scene_planes.cpp), what remains
// is split into Euclidean clusters (PCL, scene_clusters.cpp), and the plant is the thin-parted
// cluster the camera is aimed at.
// Its pot, the thick part it stands in at its bottom, is removed. A scene where no cluster is
// thin enough to be leaves has no plant.
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "segmentation/scene_clusters.h"
#include "segmentation/scene_planes.h"
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

using namespace scene;

// What the plane removal leaves of a floor or wall, along its borders and where its readings
// spread beyond the tolerance, lies within a few tolerances of it; a plant stands out of the
// floor and before the wall. A cluster with most of its pixels this close to a removed plane is
// a remnant, not an object.
constexpr float kRemnantTolerances = 2.f;
constexpr float kMaxRemnantShare = 0.6f;
// How far apart two pieces of one plant lie, near the camera. What parts them is what the
// sensor did not read between them, or read as a jump; both widen as its readings scatter, with
// depth squared, so the reach grows as a plane's tolerance does (7.8 cm at 2.2 m).
constexpr float kLeafGap_m = 0.03f;
// A piece that joins the plant is held to less: slivers of the floor and wall beside the plant
// lie within its reach.
constexpr float kMaxJoinedRemnantShare = 0.2f;
// A pot stands on the floor, a table top or the ground: its lowest reading lies within this of
// it (a camera looking down sees its bottom rim hidden, the plane's removal takes a few cm).
// A broad leaf's base in a piece of the plant that broke off lies well above.
constexpr float kPotStandsWithin_m = 0.2f;
// The objects left out that the debug overlay outlines: the largest, down to an eighth of what a
// plant covers at least.
constexpr std::size_t kMaxLeftOut = 12;
constexpr int kLeftOutShareOfPlant = 8;
// What the plant's own pot is called where it is outlined among the objects left out.
constexpr const char* kPotWhy = "pot";
// A seedling in its pot seen edge-on covers few pixels; what stands in a pot of its own, thin, is
// a plant down to this share of a plant's pixels. The room's odd ends that small stand in none.
constexpr int kSeedlingShareOfPlant = 2;
// What a user whose plant is thin but only too small (over half a plant's pixels) should do.
constexpr const char* kBringCloser = ": bring the camera closer if it is the plant";
// Beyond the distances the guide tests (docs/capture.md, up to 1.2 m) a broad-leaved plant's
// leaves blur into one another on a time-of-flight or stereo camera, and its parts measure too
// short for their width; nearer, they part.
constexpr float kGuideFarthest_m = 1.2f;
constexpr const char* kBroadBringCloser =
    ": bring the camera closer if it is a broad-leaved plant (from afar its leaves blur into one "
    "another)";

// Whether a far object misses a leaf's shape only as a broad-leaved plant's blurred leaves do:
// parts wide enough for broad leaves and long enough for leaves, not for broad ones.
bool broadLeavesBlurredFromAfar(const PartShape& shape, float depth_m, const SegmenterParams& p) {
    return depth_m > kGuideFarthest_m && shape.width_m > p.plantMaxMeanWidth_m &&
           shape.width_m <= kBroadLeafWidthShare * p.plantMaxMeanWidth_m &&
           shape.elongation >= kMinLeafElongation;
}

// Whether the mask runs off the top of what the sensor read along more than a few columns
// (one stray pixel there is a leaf's tip, at most).
bool runsOffTop(const cv::Mat1b& mask, const SensedExtent& sensed) {
    constexpr int kMinColumns = 4;
    int columns = 0;
    for (int x = 0; x < mask.cols; ++x) {
        const int top = sensed.firstY[static_cast<std::size_t>(x)];
        for (int y = std::max(0, top - 1); y <= std::min(mask.rows - 1, top + 1); ++y)
            if (mask(y, x)) {
                ++columns;
                break;
            }
    }
    return columns >= kMinColumns;
}

// The outer contour of `mask`'s largest part, frame pixels; empty for an empty mask.
std::vector<cv::Point> largestOutline(const cv::Mat1b& mask) {
    const cv::Rect box = cv::boundingRect(mask);
    if (box.empty()) return {};
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask(box).clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE,
                     box.tl());
    if (contours.empty()) return {};
    return *std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
        return cv::contourArea(a) < cv::contourArea(b);
    });
}

// The objects not taken for the plant's (`joined` 0) and at least `minArea_px` large, largest
// first and at most kMaxLeftOut of them (a room leaves dozens), each outlined, pot and all, with
// its tag.
std::vector<LeftOutObject> leftOutObjects(const std::vector<Cluster>& clusters,
                                          const std::vector<std::string>& tag,
                                          const std::vector<char>& joined, int minArea_px) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < clusters.size(); ++i)
        if (!joined[i] && !tag[i].empty() && clusters[i].area_px >= minArea_px) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return clusters[a].area_px > clusters[b].area_px;
    });
    if (order.size() > kMaxLeftOut) order.resize(kMaxLeftOut);
    std::vector<LeftOutObject> out;
    for (const std::size_t i : order) {
        std::vector<cv::Point> outline = largestOutline(clusters[i].mask | clusters[i].pot);
        if (!outline.empty()) out.push_back({std::move(outline), tag[i]});
    }
    return out;
}

// Each cluster's share of pixels within kRemnantTolerances of a removed plane.
void measureNearPlanes(std::vector<Cluster>& clusters, const std::vector<ScenePlane>& planes,
                       const cv::Mat1w& depth_mm, const Intrinsics& k, const SegmenterParams& p) {
    for (Cluster& c : clusters) {
        int near = 0;
        const cv::Rect box = cv::boundingRect(c.mask);
        for (int y = box.y; y < box.y + box.height; ++y)
            for (int x = box.x; x < box.x + box.width; ++x) {
                if (!c.mask(y, x)) continue;
                const glm::vec3 v = k.backProject(static_cast<float>(x), static_cast<float>(y),
                                                  depth_mm(y, x) / kMillimetresPerMetre);
                const float tolerance_m =
                    kRemnantTolerances * planeTolerance_m(p.scenePlaneDistance_m, v.z);
                for (const ScenePlane& plane : planes)
                    if (planeDistance_m(plane, v) <= tolerance_m) {
                        ++near;
                        break;
                    }
            }
        c.nearPlanes = static_cast<float>(near) / static_cast<float>(std::max(1, c.area_px));
    }
}

// The clusters sorted out: those that could be a plant, why each other is not, and what to tell
// a user when none could.
struct Sorting {
    std::vector<std::size_t> thin;  // thin, large, borne and below the view's top: candidates
    std::vector<std::string> tag;   // why each is not a plant, in a few words (empty: it could be)
    // Why the largest object is not a plant, for a user whose plant was not found.
    std::string largestUnlike;
    std::size_t largestIndex = 0;
    // And the largest object only too small to be one: a plant too far away, most likely, once
    // it covers half the least a plant does.
    std::string largestSmall;
    std::size_t largestSmallIndex = 0;
    int offTop = 0;   // thin and large enough, but running off the top of the view
    int unborne = 0;  // thin and large enough, but nothing in view to stand on
};

// Where the plant stands: the top middle of its pot, or else the middle of its lowest row.
cv::Point2f footOf(const cv::Mat1b& plant, const cv::Mat1b& pot) {
    const bool inPot = cv::countNonZero(pot) > 0;
    const cv::Mat1b& foot = inPot ? pot : plant;
    const cv::Rect footBox = cv::boundingRect(foot);
    const int footRow = inPot ? footBox.y : footBox.y + footBox.height - 1;
    std::vector<cv::Point> row;
    cv::findNonZero(foot.row(footRow), row);
    float sum = 0.f;
    for (const cv::Point& q : row) sum += static_cast<float>(q.x);
    return {row.empty() ? footBox.x + 0.5f * footBox.width : sum / row.size(),
            static_cast<float>(footRow)};
}

// Whether the cluster stands in a pot (`pot` taken off it) on a floor, a table top or the ground.
bool standsInItsPot(const Cluster& c, const std::vector<ScenePlane>& planes,
                    const cv::Mat1w& depth_mm, const Intrinsics& k) {
    return cv::countNonZero(c.pot) > 0 &&
           aboveBearing_m(c.pot, depth_mm, k, planes) <= kPotStandsWithin_m;
}

// Whether the cluster grows out of a pot as a plant does: its thick base is shaped like a pot, at
// least half as tall as wide in the image (a chair's leg lying along the floor is a long flat
// base), and its thin part rises from the middle of the pot's top: it has readings within the
// pot's middle half of columns, just above the top.
constexpr float kPotMinHeightOverWidth = 0.5f;
bool growsOutOfItsPot(const Cluster& c) {
    const cv::Rect pot = cv::boundingRect(c.pot);
    if (static_cast<float>(pot.height) < kPotMinHeightOverWidth * static_cast<float>(pot.width))
        return false;
    const cv::Point2f foot = footOf(c.mask, c.pot);
    const int reach = std::max(3, pot.height / 4);
    const cv::Rect above(static_cast<int>(foot.x) - pot.width / 4, static_cast<int>(foot.y) - reach,
                         std::max(1, pot.width / 2), reach);
    return cv::countNonZero(c.mask(above & cv::Rect({}, c.mask.size()))) > 0;
}

// Takes each cluster's pot (the thick part it stands in) off it and measures what grows out of
// it against a plant's leaves.
Sorting sortOut(std::vector<Cluster>& clusters, const std::vector<ScenePlane>& planes,
                const cv::Mat1w& depth_mm, const Intrinsics& k, const SegmenterParams& p,
                int minArea_px) {
    Sorting out;
    out.tag.resize(clusters.size());
    out.largestIndex = out.largestSmallIndex = clusters.size();
    int largestArea_px = 0, largestSmallArea_px = minArea_px / 2;
    const SensedExtent sensed = SensedExtent::of(depth_mm);
    // A plant stands on a floor, a table top or the ground, and the guide keeps its base in
    // view. With none in view, what is thin and long is a strip of the room (a curtain's edge
    // against the far wall, a shelf's), or the camera looks where no foot can be found.
    const bool bearingInView = std::any_of(planes.begin(), planes.end(), bearsThings);
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        Cluster& c = clusters[i];
        // A pot, a box on the floor, a chair's seat: what stands thick on its bottom goes first,
        // so that the parts measured are what grows out of it.
        c.pot = thickBase(c.mask, c.medianDepth_m, k);
        const cv::Mat1b whole = c.mask.clone();
        c.mask &= ~c.pot;
        c.area_px = cv::countNonZero(c.mask);
        if (c.area_px == 0) continue;
        const PartShape shape = partShape(c.mask, c.medianDepth_m, k, true, whole);
        c.meanWidth_m = shape.width_m;
        // What keeps it from being a plant, empty when nothing does.
        std::ostringstream why;
        why.precision(2);
        std::string& tag = out.tag[i];
        if (const std::string parts = unlikeLeafParts(shape, p); !parts.empty()) {
            why << "is " << parts;
            if (broadLeavesBlurredFromAfar(shape, c.medianDepth_m, p)) why << kBroadBringCloser;
            tag = shape.width_m > p.plantMaxMeanWidth_m ? "too wide" : "too short for its width";
        } else if (c.nearPlanes > kMaxRemnantShare) {
            why << "lies along the floor or a wall (what their removal left)";
            tag = "floor or wall";
        } else if (c.height_m < p.plantMinHeight_m ||
                   (c.area_px < minArea_px &&
                    !(c.area_px >= minArea_px / kSeedlingShareOfPlant &&
                      standsInItsPot(c, planes, depth_mm, k) && growsOutOfItsPot(c)))) {
            tag = "too small";
            why << "is too small (" << c.area_px << " px; a plant: at least " << minArea_px
                << " px and " << p.plantMinHeight_m * 100 << " cm tall)";
            if (c.area_px > largestSmallArea_px) {
                largestSmallArea_px = c.area_px;
                out.largestSmallIndex = i;
                std::ostringstream small;
                small.precision(2);
                small << "the largest thin one, " << c.height_m << " m tall at " << c.medianDepth_m
                      << " m, " << why.str() << kBringCloser;
                out.largestSmall = small.str();
            }
        }
        const std::string unlike = why.str();
        if (c.area_px > largestArea_px) {
            largestArea_px = c.area_px;
            out.largestIndex = i;
            std::ostringstream largest;
            largest.precision(2);
            if (!unlike.empty())
                largest << "the largest, " << c.height_m << " m tall at " << c.medianDepth_m
                        << " m, " << unlike;
            out.largestUnlike = largest.str();
        }
        if (!unlike.empty()) continue;
        // A plant put before the camera is seen up to its top leaves; what goes on above the
        // view (a door's frame, a curtain, a lamp's pole) is the room's.
        if (runsOffTop(c.mask, sensed)) {
            ++out.offTop;
            tag = "runs off the top";
        } else if (!bearingInView) {
            ++out.unborne;
            tag = "nothing to stand on";
        } else {
            out.thin.push_back(i);
        }
    }
    return out;
}

// "no plant in view: ..." with what was seen instead.
std::string noPlantReason(const Sorting& s, std::size_t clusters, const SegmenterParams& p) {
    std::ostringstream why;
    why.precision(2);
    why << "no plant in view: ";
    if (clusters == 0)
        why << "nothing stands apart from the floor and walls";
    else
        why << clusters << " object(s) stand apart from the floor and walls, none "
            << "large enough and made of parts under " << p.plantMaxMeanWidth_m * 100
            << " cm wide and " << kMinLeafElongation << " times as long, as leaves are";
    if (!s.largestUnlike.empty()) why << "; " << s.largestUnlike;
    if (!s.largestSmall.empty())  // the largest itself, or another
        why << (s.largestSmallIndex == s.largestIndex ? std::string(kBringCloser)
                                                      : "; " + s.largestSmall);
    if (s.offTop > 0)
        why << "; " << s.offTop << " that run(s) off the top of the view (a plant too near "
            << "the camera, or a pole or frame of the room)";
    if (s.unborne > 0)
        why << "; " << s.unborne
            << " thin enough, but no floor, table top or ground in view (a plant "
            << "stands on one: keep it in view, the camera upright)";
    return why.str();
}

// The one the camera is aimed at: nearest the image's centre, among those at least a tenth the
// size of the largest thin one (a stray leaf of the clutter is not the subject).
std::size_t aimedAt(const std::vector<Cluster>& clusters, const std::vector<std::size_t>& thin,
                    cv::Size frame) {
    int largest = 0;
    for (std::size_t i : thin) largest = std::max(largest, clusters[i].area_px);
    const cv::Point2f centre(0.5f * static_cast<float>(frame.width),
                             0.5f * static_cast<float>(frame.height));
    std::size_t chosen = thin.front();
    float best = std::numeric_limits<float>::max();
    for (std::size_t i : thin) {
        if (10 * clusters[i].area_px < largest) continue;
        const float d = static_cast<float>(cv::norm(clusters[i].centroid_px - centre));
        if (d < best) best = d, chosen = i;
    }
    return chosen;
}

// A plant whose leaves meet only at a stem the sensor hardly reads, or only across depth jumps,
// falls apart into one cluster a leaf: the thin clusters whose bounds come within the leaf gap
// at the plant's depth of the plant's join it (`chosen`), in turn; not what stood on something
// thick (a box's remains) nor slivers of the floor and wall. Returns which joined; tags those
// thin ones that did not.
std::vector<char> joinThePlantsPieces(std::vector<Cluster>& clusters, std::size_t chosen,
                                      Sorting& sorting, const std::vector<ScenePlane>& planes,
                                      const cv::Mat1w& depth_mm, const Intrinsics& k,
                                      const SegmenterParams& p) {
    Cluster& c = clusters[chosen];
    // A thick base high above the floor is a broad leaf's, in a piece the plant broke into: no
    // pot, and the piece's own. Each object's is measured once: a room leaves dozens.
    std::vector<char> potStands(clusters.size(), 0);
    for (std::size_t i = 0; i < clusters.size(); ++i)
        potStands[i] = standsInItsPot(clusters[i], planes, depth_mm, k);
    const auto restorePot = [&](std::size_t i) {
        Cluster& o = clusters[i];
        if (potStands[i]) return;
        o.mask |= o.pot;
        o.pot.setTo(0);
    };
    restorePot(chosen);
    std::vector<char> joined(clusters.size(), 0);
    joined[chosen] = 1;
    // A plant stands in one pot. Where the piece aimed at stands in none (a broad leaf before
    // the stem, broken off by the depth jumps around it), a larger thin object beside it that
    // does is the rest of the plant; a smaller one, a box's remains.
    bool standsInPot = potStands[chosen] != 0;
    const float leafGap_m = planeTolerance_m(kLeafGap_m, c.medianDepth_m);
    const int pieceArea_px = c.area_px;
    std::vector<char> isThin(clusters.size(), 0);
    for (const std::size_t i : sorting.thin) isThin[i] = 1;
    for (bool grew = true; grew;) {
        grew = false;
        for (std::size_t i = 0; i < clusters.size(); ++i) {
            const Cluster& o = clusters[i];
            const bool plantsPot =
                potStands[i] && !standsInPot && isThin[i] && o.area_px > pieceArea_px;
            if (joined[i] || o.area_px == 0 || o.meanWidth_m > p.plantMaxMeanWidth_m ||
                o.nearPlanes > kMaxJoinedRemnantShare || (potStands[i] && !plantsPot) ||
                !boundsMeet(c, o, leafGap_m))
                continue;
            joined[i] = 1;
            standsInPot = standsInPot || plantsPot;
            restorePot(i);
            grew = true;
            c.mask |= o.mask;
            c.pot |= o.pot;
            for (int a = 0; a < 3; ++a) {
                c.lo[a] = std::min(c.lo[a], o.lo[a]);
                c.hi[a] = std::max(c.hi[a], o.hi[a]);
            }
        }
    }
    c.area_px = cv::countNonZero(c.mask);
    for (const std::size_t i : sorting.thin)
        if (!joined[i])
            sorting.tag[i] = potStands[i] ? "stands in a pot of its own" : "apart from the plant";
    return joined;
}

}  // namespace

FoundPlant findPlant(const cv::Mat1w& depth_mm, const Intrinsics& k, const SegmenterParams& p,
                     StageReport& report) {
    FoundPlant plant;
    cv::Mat1b rest = (depth_mm > 0) & (depth_mm <= p.sceneMaxDepth_m * kMillimetresPerMetre);
    const std::vector<ScenePlane> planes = removeScenePlanes(depth_mm, k, p, rest, report);
    std::vector<Cluster> clusters = euclideanClusters(depth_mm, k, p, rest);
    measureNearPlanes(clusters, planes, depth_mm, k, p);
    // A pixel spans 1 / (fx fy) steradians near the optical axis.
    const int minArea_px =
        static_cast<int>(std::min(p.plantMinImageShare * static_cast<float>(depth_mm.total()),
                                  p.plantMinSolidAngle_sr * k.fx_px * k.fy_px));
    Sorting sorting = sortOut(clusters, planes, depth_mm, k, p, minArea_px);
    report.notes.push_back(std::to_string(clusters.size()) + " cluster(s) after " +
                           std::to_string(planes.size()) + " scene plane(s), " +
                           std::to_string(sorting.thin.size()) + " thin enough to be a plant");
    if (sorting.thin.empty()) {
        plant.whyNot = noPlantReason(sorting, clusters.size(), p);
        plant.leftOut = leftOutObjects(clusters, sorting.tag, std::vector<char>(clusters.size(), 0),
                                       minArea_px / kLeftOutShareOfPlant);
        return plant;
    }
    const std::size_t chosen = aimedAt(clusters, sorting.thin, depth_mm.size());
    const std::vector<char> joined =
        joinThePlantsPieces(clusters, chosen, sorting, planes, depth_mm, k, p);
    plant.leftOut =
        leftOutObjects(clusters, sorting.tag, joined, minArea_px / kLeftOutShareOfPlant);
    const Cluster& c = clusters[chosen];
    const cv::Mat1b& pot = c.pot;
    std::ostringstream note;
    note.precision(2);
    note << "plant: " << c.area_px << " px, " << c.height_m << " m tall at " << c.medianDepth_m
         << " m, parts " << c.meanWidth_m * 100 << " cm wide; pot " << cv::countNonZero(pot)
         << " px removed";
    report.notes.push_back(note.str());
    plant.found = true;
    plant.mask = c.mask;
    // The pot is taken off the plant too: outlined, a user sees where the plant's lowest leaves
    // went when they hang before it or crowd its rim.
    if (std::vector<cv::Point> outline = largestOutline(pot); !outline.empty())
        plant.leftOut.insert(plant.leftOut.begin(), {std::move(outline), kPotWhy});
    plant.base_px = footOf(c.mask, pot);
    if (cv::countNonZero(pot) > 0) plant.pot_px = cv::boundingRect(pot);
    double nearest = 0, farthest = 0;
    cv::minMaxLoc(depth_mm, &nearest, &farthest, nullptr, nullptr, c.mask);
    plant.near_m = static_cast<float>(nearest) / kMillimetresPerMetre;
    plant.far_m = static_cast<float>(farthest) / kMillimetresPerMetre;
    // Trail candidates: readings of the plant's depth range that no plane and no other cluster
    // holds (a dotted tip falls apart into samples too few to be a cluster of its own).
    plant.candidates = rest & (depth_mm >= nearest) & (depth_mm <= farthest);
    for (std::size_t i = 0; i < clusters.size(); ++i)
        if (!joined[i]) plant.candidates &= ~clusters[i].mask;
    plant.candidates &= ~pot;
    plant.candidates |= plant.mask;
    return plant;
}

}  // namespace meadow::capture::segmentation
