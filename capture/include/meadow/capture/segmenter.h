#pragma once
// Segmentation: depth frames -> one ordered contour per blade (Fan & Sheng 2017, Sec. 4.1-4.2).
//
// Pipeline, one stage per file under capture/src/segmentation/:
//   temporal fusion (optional, several frames of a still tuft: per-pixel median)
//   -> depth-band mask (user band or the nearest dominant depth mode)
//   -> ground / background plane removal (PCL: RANSAC or organized multi-plane)
//   -> outlier removal (organized neighbourhood test, or PCL statistical outlier removal)
//   -> morphological clean-up (closing, small regions, small holes)
//   -> contours and cluster reference point (contour centre or base point)
//   -> partition at persistent minima of the distance to the reference point
//   -> per-blade contour, mask and flags.
// Every stage records what it dropped and why in Segmentation::report; every flag carries a
// reason. Frames with nothing to segment give an empty result with Segmentation::noBladesReason
// set, never an exception; broken input (wrong image type, mismatched sizes, unusable
// intrinsics) throws CaptureError.
#include <filesystem>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "meadow/capture/blade_contour.h"
#include "meadow/capture/depth_frame.h"
#include "meadow/capture/recurring_readings.h"
#include "meadow/core/enum_names.h"

namespace meadow::capture {

enum class PlaneMethod {
    None,                 // keep every point of the depth band
    Ransac,               // pcl::SACSegmentation, SACMODEL_PLANE, on a strided sample
    OrganizedMultiPlane,  // pcl::OrganizedMultiPlaneSegmentation + integral-image normals
};
enum class OutlierMethod {
    None,
    OrganizedNeighbourhood,  // per pixel: enough neighbours within a depth tolerance (cheap)
    Statistical,             // pcl::StatisticalOutlierRemoval on the masked points
};
enum class ReferencePoint {
    ContourCentre,  // centroid of the cluster (Fan & Sheng 2017, Sec. 4.2)
    BasePoint,      // lowest part of the cluster, where the blades of a side-viewed tuft meet
};
enum class BladeMaskMethod {
    NearestContour,  // each cluster pixel to the blade whose contour piece is nearest
    Wedge,  // inside exactly one blade's piece closed through the base point: that blade; else
            // NearestContour (needs ReferencePoint::BasePoint; with the centre it is
            // NearestContour)
};
// How a cluster is cut into blades.
enum class PartitionMethod {
    Contour,    // Fan & Sheng 2017: minima of the contour's distance to the base (a fan of blades)
    StemGraph,  // the skeleton's tree from the base: leaves cut where they leave a stem
};
// How the plant is told from the rest of the scene when no depth band is given.
enum class PlantFinding {
    DepthMode,  // the nearest dominant depth mode (a tuft before a far background)
    Clusters,   // the room's planes removed, Euclidean clusters, the thin one in the middle
};
// What the camera looks at; it picks the plant finding and the partition measured best on it
// (docs/measurements/plant_benchmark.md).
enum class Subject {
    Tuft,         // blades fanning from one base, before a background: DepthMode + Contour
    PottedPlant,  // leaves off a stem, a pot, a room about it: Clusters + StemGraph
};
// How several frames of a still tuft become one depth image (temporal fusion).
enum class FusionMethod {
    Median,  // per-pixel median of the valid readings (Fan & Sheng 2017)
    // Per pixel, the nearest depth that at least fusionRecurringShare of the frames read within
    // fusionAgreement_mm of one another (recurring_readings.h); the median where none recurs.
    // Lateral noise hands a blade under ~2 px wide to the wall behind in half the frames or
    // more, a different half each time, so the median keeps the wall there.
    NearestRecurring,
};

inline constexpr EnumNames<PlaneMethod, 3> kPlaneMethodNames{{{
    {PlaneMethod::None, "none"},
    {PlaneMethod::Ransac, "ransac"},
    {PlaneMethod::OrganizedMultiPlane, "organized-multi-plane"},
}}};
inline constexpr EnumNames<PartitionMethod, 2> kPartitionMethodNames{{{
    {PartitionMethod::Contour, "contour"},
    {PartitionMethod::StemGraph, "stem-graph"},
}}};
inline constexpr EnumNames<PlantFinding, 2> kPlantFindingNames{{{
    {PlantFinding::DepthMode, "depth-mode"},
    {PlantFinding::Clusters, "clusters"},
}}};
inline constexpr EnumNames<Subject, 2> kSubjectNames{{{
    {Subject::Tuft, "tuft"},
    {Subject::PottedPlant, "potted-plant"},
}}};
inline constexpr EnumNames<FusionMethod, 2> kFusionMethodNames{{{
    {FusionMethod::Median, "median"},
    {FusionMethod::NearestRecurring, "nearest-recurring"},
}}};
inline constexpr EnumNames<OutlierMethod, 3> kOutlierMethodNames{{{
    {OutlierMethod::None, "none"},
    {OutlierMethod::OrganizedNeighbourhood, "organized-neighbourhood"},
    {OutlierMethod::Statistical, "statistical"},
}}};
inline constexpr EnumNames<ReferencePoint, 2> kReferencePointNames{{{
    {ReferencePoint::ContourCentre, "contour-centre"},
    {ReferencePoint::BasePoint, "base-point"},
}}};
inline std::string toString(PlaneMethod m) { return std::string(kPlaneMethodNames.name(m)); }
inline std::string toString(FusionMethod m) { return std::string(kFusionMethodNames.name(m)); }
inline std::string toString(OutlierMethod m) { return std::string(kOutlierMethodNames.name(m)); }
inline std::string toString(ReferencePoint r) { return std::string(kReferencePointNames.name(r)); }

struct SegmenterParams {
    // --- Depth band (Sec. 4.1). nearDepth_m < farDepth_m sets the band; both 0 = automatic:
    // the nearest histogram mode holding >= minModeFraction of the valid pixels (and at least
    // minRegionArea_px) that does not span most image columns (that is ground or a wall seen
    // edge-on), widened to the histogram valleys on both sides. The fraction is small because a
    // back wall can hold 100x the pixels of a single blade.
    float nearDepth_m = 0.0f;
    float farDepth_m = 0.0f;
    float histogramBin_m = 0.01f;
    float minModeFraction = 0.002f;
    float maxBandHalfWidth_m =
        0.15f;  // the automatic band spans at most this each side of its mode (a tuft's depth)
    // The automatic band then grows into neighbouring pixels whose depth differs by at most
    // this from an in-band neighbour (tips leaning toward or away from the camera leave the
    // histogram mode but stay depth-continuous with their blade); 0 = no growth.
    float bandGrowStep_m = 0.015f;

    // --- Plant finding without a band (docs/capture.md#finding-the-plant).
    PlantFinding plantFinding = PlantFinding::DepthMode;
    float sceneMaxDepth_m = 5.0f;         // Clusters: readings beyond are the room, not the plant
    float scenePlaneDistance_m = 0.015f;  // a floor or wall's inlier tolerance near the camera
                                          // (it grows with depth as the sensor's noise does)
    float minScenePlaneShare = 0.08f;     // a floor or wall holds this share of the readings
    int maxScenePlanes = 4;               // floor, two walls, a table top
    float clusterTolerance_m = 0.02f;     // points nearer than this are one object
    int minClusterPoints = 50;            // on every 2nd pixel of every 2nd row
    // A plant is made of thin parts: the median over its pixels of twice the distance to its
    // edge (a leaf's width, about) at most plantMaxMeanWidth_m, after the thick part it stands
    // in (a pot) is taken off; and it stands at least plantMinHeight_m tall. Boxes, furniture,
    // a tray of lettuce seen from above: thicker.
    float plantMaxMeanWidth_m = 0.04f;
    float plantMinHeight_m = 0.05f;
    // ...and covers at least this share of the image, or this solid angle (steradians; 0.0089
    // is 0.8 % of a Kinect's 640 x 480 view at 525 px focal length), whichever is fewer pixels:
    // the guide frames the plant to fill much of the view
    // (docs/capture.md#capturing-your-own-plant), and the room's odd ends are smaller. A
    // wide-angle camera sees the same plant at the same distance on a smaller share of its
    // image; the angle keeps it.
    float plantMinImageShare = 0.008f;
    float plantMinSolidAngle_sr = 0.0089f;

    // --- Ground / background plane removal.
    // RANSAC: organized multi-plane is faster, but its integral-image normals break at dropout
    // holes and it then finds no ground (see docs/capture.md#plane-removal).
    PlaneMethod planeMethod = PlaneMethod::Ransac;
    float planeDistance_m = 0.012f;  // inlier tolerance; > sensor noise at 1-1.5 m
    float minPlaneFraction = 0.02f;  // a plane must hold this share of the masked pixels (the
                                     // ground seen at grazing angles reads mostly 0)
    // Only ground-like planes are removed: the normal within this angle of the camera's up
    // axis (-y), i.e. a camera pitched up to this much. The back wall is left to the depth band,
    // and planes through a fan of blades or the wall-floor corner, which tilt further, are kept.
    float maxGroundTilt_deg = 45.0f;
    int maxPlanes = 1;
    int planeSampleStride_px = 2;  // RANSAC fits on every n-th pixel, inliers use all pixels
    int ransacIterations = 200;

    // --- Outlier removal (flying pixels, speckle).
    OutlierMethod outlierMethod = OutlierMethod::OrganizedNeighbourhood;
    int outlierWindow_px = 5;      // odd neighbourhood size
    int outlierMinNeighbours = 4;  // neighbours within the tolerance needed to stay
    float outlierDepthTolerance_m = 0.03f;
    int statisticalMeanK = 16;          // Statistical: neighbours for the mean distance
    float statisticalStddevMul = 1.5f;  // Statistical: threshold in standard deviations

    // --- Temporal fusion: a pixel needs a reading in at least this share of the frames.
    float minValidFrameFraction = 0.5f;
    FusionMethod fusion = FusionMethod::Median;
    // NearestRecurring: the share of the frames (at least 2 of them) that must agree on a depth.
    float fusionRecurringShare = 0.34f;
    int fusionAgreement_mm = 10;

    // --- Morphological clean-up.
    int closeKernel_px = 3;  // 0 or 1 = no closing; closing bridges 1 px dropouts
    // Edge smoothing: the contour's points averaged along it by a Gaussian of this sigma (in
    // contour points), each moved at most edgeSmoothingMaxShift_px, and the mask redrawn from
    // them; tips, valleys between blades and parts under 3 px wide are kept
    // (contour_smoothing.cpp). It undoes the sensor's ragged edge (lateral noise moves edge
    // pixels ~0.8 px each way) better than a blur of the mask does. 0 = off
    // (see docs/capture.md#clean-up-and-edge-smoothing).
    float edgeSmoothingSigma_px = 4.0f;
    float edgeSmoothingMaxShift_px = 1.0f;  // about the lateral noise; larger hurts sharp tips
    int openKernel_px = 0;                  // opening removes thin blades too, so off by default
    int minRegionArea_px = 60;              // connected regions smaller than this are dropped
    int maxHoleArea_px = 30;                // enclosed holes up to this size are filled (dropouts)

    // --- Tip trails: a tip under ~2 px wide reaches the mask as a dotted line of in-band
    // readings (lateral noise gives about half of them to the background), which outlier
    // removal and clean-up drop. Groups of such readings, gaps up to tipTrailGap_px, that start
    // at the mask and reach at least tipTrailMinReach_px from it are linked back one pixel wide;
    // edge speckle beside a blade reaches 1-2 px. A group that meets the mask in several places
    // (neighbouring tips joined through readings between them) is split there, each part a
    // trail of its own. 0 = off.
    float tipTrailMinReach_px = 4.0f;
    int tipTrailGap_px = 2;
    int tipTrailMaxLength_px = 48;  // how far from the mask's box a trail is searched
    // Trails are not followed when edges are this ragged (Segmentation::edgeRaggedness), well
    // above a Kinect's nominal noise: beyond it speckle chains reach as far as tips, and
    // following them costs recall (see docs/capture.md#tip-trails).
    float tipTrailMaxRaggedness = 0.1f;

    // Thin fragments: a part of the cleaned mask of at most fragmentMaxArea_px that is at least
    // fragmentMinAspect times as long as wide is joined to another part lying past one of its
    // ends within fragmentLinkGap_px and fragmentLinkAngle_deg of its axis (0 gap = off): a
    // blade under ~3 px wide comes out of the sensor as a stalk and fragments
    // (see docs/capture.md#thin-fragment-links).
    float fragmentLinkGap_px = 10.0f;
    int fragmentMaxArea_px = 600;
    float fragmentMinAspect = 4.0f;
    float fragmentLinkAngle_deg = 30.0f;

    // --- Partition (Sec. 4.2).
    PartitionMethod partition = PartitionMethod::Contour;
    // StemGraph: a skeleton branch shorter than this from its tip to the stem is a spur of the
    // edge, not a leaf (docs/capture.md#partition-by-the-stem).
    float minLeafBranch_px = 15.0f;
    // StemGraph: at a junction of the skeleton an edge continues the one it turns least from,
    // if it turns less than crossingMaxBend_deg and, where both have readings, their depths
    // carried to the junction differ by less than crossingDepthStep_mm: a leaf crossing another
    // or the stem stays one leaf (docs/capture.md#partition-by-the-stem).
    float crossingMaxBend_deg = 45.0f;
    float crossingDepthStep_mm = 100.0f;
    // StemGraph: two pieces of the mask whose skeletons end facing each other, this near in
    // space and turning less than crossingMaxBend_deg to meet, are one leaf the sensor did not
    // read along a stretch, and are joined (0 = off; docs/capture.md#partition-by-the-stem).
    float leafGapBridge_m = 0.03f;
    ReferencePoint reference = ReferencePoint::BasePoint;
    float baseBandFraction = 0.05f;  // BasePoint: lowest share of the cluster's height used
    float smoothingSigma_px = 2.0f;  // Gaussian along the contour, in contour samples
    // A local minimum of the distance cuts the contour when its persistence (depth below the
    // lower of the two maxima that bound it) reaches max(minPersistence_px,
    // minPersistenceFraction x the largest distance).
    float minPersistence_px = 6.0f;
    float minPersistenceFraction = 0.06f;
    int minBladeContour_px = 12;  // contour pieces shorter than this merge into a neighbour
    // Which blade owns the shared base below the forks, where blades overlap. NearestContour
    // gives the whole base to the two outermost blades, whose contour pieces enclose it; Wedge
    // shares it out (see docs/capture.md#partition-and-fork-zone).
    BladeMaskMethod bladeMask = BladeMaskMethod::Wedge;
    // Wedge only, where depth is known: the fork zone (the triangles between each blade's
    // valleys and the base point) is decided again by each blade's centre line continued to the
    // base and by depth, since a blade in front covers its neighbours' lower parts there
    // (fork_partition.cpp; see docs/capture.md#partition-and-fork-zone). forkDepthSigma_mm
    // weighs a depth difference against half a half width off the centre line. Not where the
    // edges are ragged beyond forkMaxRaggedness: there the continued centre lines lose.
    bool forkByDepth = true;
    float forkDepthSigma_mm = 3.0f;
    float forkMaxRaggedness = 0.03f;

    // --- Flags.
    float minResolvableWidth_px = 2.0f;  // TooThin below this mean width
    // TooThin also when fewer of the blade's pixels than this survive a 3x3 erosion (lie over a
    // pixel inside its edge): a blade under ~3 px wide. The mean width (area / centre line)
    // misses such blades under noise, which widens their ragged masks. The threshold lies below
    // what matched leaves keep and above most unmatched slim-grass pieces
    // (see docs/capture.md#flags). 0 = off.
    float minInteriorFraction = 0.2f;
    // ...when the edges are ragged (Segmentation::edgeRaggedness at least this, between
    // noise-free frames and a Kinect's nominal noise). On clean edges a 2-3 px blade is
    // resolved, and the test would flag blades that match.
    float raggedEdges = 0.01f;
    // CurlsSideways when the centre line turns more than curlTurn_deg and the quadratic spine
    // that fits it best misses it by more than curlMissShare of its length: an arching leaf
    // (rising, then drooping) turns as much but the blade model holds it.
    float curlTurn_deg = 150.0f;
    float curlMissShare = 0.08f;
    float overlapWidthRatio = 2.2f;  // Overlapping when this much wider than the median
    // Overlapping when a blade's contour dips between two tips by at least this share of the
    // cut threshold: too shallow to cut, deep enough for two blades that touch (clean leaf
    // pieces dip far less, merged touching blades far more).
    float secondTipFraction = 0.4f;

    // Sets plantFinding and partition to those measured best on the subject.
    void setSubject(Subject subject);

    // Empty when usable; otherwise what is wrong with the parameters.
    [[nodiscard]] std::string problem() const;
};

// What one stage removed, and why.
struct StageReport {
    std::string stage;               // "depth band", "plane removal", ...
    int droppedPixels = 0;           // pixels removed from the mask by this stage
    int keptPixels = 0;              // mask pixels after the stage
    double time_ms = 0.0;            // wall time of the stage
    std::vector<std::string> notes;  // "dropped 3 regions < 60 px", "plane n=(..) 41 % of band"
};

// An object that plant finding (PlantFinding::Clusters) saw standing apart from the floor and
// walls and did not take for the plant's, with why in a few words.
struct LeftOutObject {
    std::vector<cv::Point> outline_px;  // its outer contour, frame pixels
    std::string why;                    // "too wide", "too small", "apart from the plant", ...
};

// A connected foreground region: the tuft, normally one per frame.
struct BladeCluster {
    std::vector<cv::Point> contour_px;  // outer contour, CHAIN_APPROX_NONE, counter-clockwise
    cv::Point2f centre_px;              // contour centre (centroid of the region)
    cv::Point2f basePoint_px;           // lowest part of the region
    cv::Point2f reference_px;           // the one used for the partition (params.reference)
    std::vector<int> cutIndices;        // indices into contour_px where blades meet
    std::vector<float> distance_px;     // smoothed distance to reference along the contour
    std::vector<int> bladeIds;          // ids of this cluster's blades in Segmentation::blades
    // PartitionMethod::StemGraph: the stem's skeleton, from where the plant stands to the
    // highest point a leaf leaves it at, in image pixels; empty when no leaves leave a stem.
    std::vector<cv::Point> stemLine_px;
    // ...and the region's pixels the stem took (those nearest its skeleton), at stemShareOrigin_px
    // in the frame: where a leaf that comes out short at its base lost it. Empty otherwise.
    cv::Mat1b stemShare;
    cv::Point stemShareOrigin_px;
    int area_px = 0;
    std::vector<BladeFlag> flags;
    std::vector<std::string> reasons;
};

struct Segmentation {
    std::vector<BladeContour> blades;
    std::vector<BladeCluster> clusters;
    cv::Mat1b clusterMask;  // foreground after clean-up (255), frame-sized
    std::vector<StageReport> report;
    float nearDepth_m = 0.0f, farDepth_m = 0.0f;  // the band actually used
    // The nearest and farthest reading the tuft's mask kept (the band grown into tips that
    // lean out of it). A reading outside is not the tuft's: a pixel that the clean-up or a tip
    // trail filled in can carry the wall behind. 0 and 0 for a given mask (segmentMask).
    float tuftNearest_m = 0.0f, tuftFarthest_m = 0.0f;
    // How ragged the sensor left the mask's edges: the share of the pixels 2-3 px outside the
    // mask that hold in-band readings (tip-trail stage); it grows with the sensor's lateral
    // noise. 0 when not measured (segmentMask).
    float edgeRaggedness = 0.0f;
    // Frames the tip trails' recurring readings were taken over (Segmenter::segment with
    // RecurringReadings); 0 when the trails saw only this segmentation's own readings.
    int recurringFrames = 0;
    // The ground the plane removal found, in camera space (metres): n.x + d = 0 with |n| = 1 and
    // n pointing up, away from the ground (n.x + d > 0 above it). Empty without a plane fit or
    // when no plane passed as ground.
    std::optional<cv::Vec4f> groundPlane;
    std::string noBladesReason;  // set when blades is empty
    // PlantFinding::Clusters found nothing in the scene that could be a plant (noBladesReason
    // says what it saw instead).
    bool noPlant = false;
    // Where the plant stands in the image (PlantFinding::Clusters: the top of its pot).
    std::optional<cv::Point2f> plantBase_px;
    // PlantFinding::Clusters, where the plant stands in a pot: the pot's box in the image.
    std::optional<cv::Rect> plantPot_px;
    // PlantFinding::Clusters: the largest objects it did not take for the plant's, and why (the
    // debug overlay outlines them), whether it found a plant or not.
    std::vector<LeftOutObject> leftOut;
    [[nodiscard]] bool empty() const { return blades.empty(); }
    [[nodiscard]] std::vector<cv::Point> cutPoints_px() const;
    [[nodiscard]] double totalTime_ms() const;
    // One line per stage and flag, for logs and the CLI.
    [[nodiscard]] std::string summary() const;
};

class Segmenter {
public:
    explicit Segmenter(SegmenterParams params = {});  // throws CaptureError if params.problem()
    ~Segmenter();
    Segmenter(Segmenter&&) noexcept;
    Segmenter& operator=(Segmenter&&) noexcept;

    [[nodiscard]] Segmentation segment(const DepthFrame& frame) const;
    // Temporal fusion: per-pixel median of the valid readings of a still tuft. All frames must
    // share size and intrinsics.
    [[nodiscard]] Segmentation segment(std::span<const DepthFrame> frames) const;
    // The same, with readings that recur over a longer run of the still tuft's frames
    // (recurring_readings.h) as further candidates for the tip trails (and for nothing else).
    [[nodiscard]] Segmentation segment(std::span<const DepthFrame> frames,
                                       const RecurringReadings& tips) const;
    // From a mask alone (no depth): clean-up, contours, partition and flags.
    [[nodiscard]] Segmentation segmentMask(const cv::Mat1b& mask) const;

    [[nodiscard]] const SegmenterParams& params() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// PNG with the depth (grey), the mask, every blade in its own colour, contours, the centre
// and base point, and the cut points (Fan & Sheng 2017, Fig. 4). Written atomically; throws
// CaptureError naming the path on failure.
void writeDebugOverlay(const std::filesystem::path& path, const DepthFrame& frame,
                       const Segmentation& segmentation);
// The same picture as an 8-bit BGR image.
[[nodiscard]] cv::Mat3b renderDebugOverlay(const DepthFrame& frame,
                                           const Segmentation& segmentation);

}  // namespace meadow::capture
