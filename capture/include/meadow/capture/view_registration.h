#pragma once
// Views of one plant that turned between them (a turntable, or a camera carried round it) are
// brought into one space: each view's plant cloud is registered to the view before it, and the
// steps chained, so that a leaf seen in several views can be told for one leaf (view_joining.h
// in modeling). A plant on a turntable turns about an upright axis through its foot: a sweep of
// turns about the up direction through the plant's lowest readings is scored, the best few are
// refined by ICP (PCL), and the one that lays most readings on the other view's is kept. A view
// that lies on none of the few views before it starts a chain of its own. At the end the last
// view is registered to the first as well, where a turntable's ends meet (see
// docs/capture.md#turntable-views).
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "meadow/capture/depth_frame.h"
#include "meadow/capture/segmenter.h"

namespace meadow::capture {

// The plant's readings in one view (camera space, metres) and the up direction there.
struct ViewCloud {
    int frame = 0;
    std::vector<glm::vec3> points_m;
    glm::vec3 up{0.f, -1.f, 0.f};  // the ground's normal, or the image's up without a ground
};

struct ViewRegistrationParams {
    int maxPoints = 1500;  // the view registered is thinned evenly to at most this many readings
    float sweepRange_deg = 90.f;     // turns tried either way between two views...
    float sweepStep_deg = 10.f;      // ...this far apart
    float maxPairing_m = 0.03f;      // ICP pairs readings at most this far apart
    float inlierDistance_m = 0.01f;  // a reading lies on the other view's within this
    // A pair is registered when this share of its readings lies on the other view's: a leaf
    // turned edge-on hides some, but below this the clouds do not share the plant.
    float minInlierShare = 0.6f;
    // A view that does not lie on the one before is tried on as many views before that (a leaf
    // turned edge-on in one view breaks no chain); 0: the view before only.
    int fallbackViews = 2;
    [[nodiscard]] std::string problem() const;  // empty when usable
};

// One view's place in its chain: reference = chainFromView * view (camera spaces, metres).
struct RegisteredView {
    int frame = 0;
    int chain = 0;  // views of one chain share a reference, the chain's first view
    glm::mat4 chainFromView{1.f};
    // The view it was registered to (-1: none, a chain's first view), the turn about the up
    // direction from it (degrees, signed) and the share of its readings that came to lie on
    // that view's.
    int registeredTo = -1;
    float turn_deg = 0.f;
    float inlierShare = 0.f;
    std::string why;  // why a chain starts here, after its first ("" otherwise)
};

// The plant mask's readings of `frame` (the segmentation's cluster mask), with the ground's
// normal as up when the segmentation found a ground.
ViewCloud plantCloud(const Segmentation& segmentation, const DepthFrame& frame);

// The share of `source`'s readings (thinned as registration thins them, params.maxPoints) that
// lie within params.inlierDistance_m of `target`'s once moved by `targetFromSource`: the figure a
// pair is registered by (params.minInlierShare). With the true motion it says whether a pair can
// be registered at all: a distant or noisy sensor's views of a thin plant share few readings.
float shareLyingOn(const ViewCloud& source, const ViewCloud& target,
                   const glm::mat4& targetFromSource, const ViewRegistrationParams& params = {});

// The turntable's ends brought together after its last view (ViewRegistrar::closeLoop): the last
// view registered to the first view of the first chain, or of its own chain when that went round
// the plant.
struct LoopClosure {
    int firstFrame = -1, lastFrame = -1;  // -1: not tried (under three views)
    // The last view lay on the first view of the first chain: its chain joined that one.
    bool joinedChains = false;
    // The last view lay on the first view of its own chain, round the plant: the drift gathered
    // along the chain was spread over its views (ELCH, PCL), taking the last view by drift_deg
    // and its plant readings by drift_mm (mean).
    bool closed = false;
    float chainTurn_deg = 0.f;  // the chain's turns added up, first view to last
    float drift_deg = 0.f, drift_mm = 0.f;
    std::string why;  // why neither ("" when one was done)
    [[nodiscard]] bool met() const { return joinedChains || closed; }
};

// Views registered one at a time as they come: each to the view before it, or failing that to
// up to params.fallbackViews views before that (their chain's), or else the first of a new chain
// with the reason it did not lie on the view before. Keeps the last few views' clouds only.
class ViewRegistrar {
public:
    explicit ViewRegistrar(ViewRegistrationParams params = {});  // throws CaptureError if unusable
    const RegisteredView& add(ViewCloud view);
    // After the last view (tried once): the last view is registered to the first view. Of
    // another chain, the last chain then joins the first; of its own chain, when that turned
    // more than half a turn, the drift is spread along it. views() then holds the new places.
    const LoopClosure& closeLoop();
    [[nodiscard]] const std::vector<RegisteredView>& views() const { return placed_; }

private:
    std::optional<glm::mat4> lastOn(const ViewCloud& target, const RegisteredView& targetPlace);
    void joinLastChainToFirst();
    void spreadLoopDrift();

    ViewRegistrationParams params_;
    std::vector<RegisteredView> placed_;
    std::vector<ViewCloud> recent_;  // the last 1 + fallbackViews views, oldest first
    ViewCloud firstView_;            // the first chain's first view
    LoopClosure loop_;
    int chains_ = 0;
};

// ViewRegistrar over the views in the order given. Throws CaptureError for unusable params.
std::vector<RegisteredView> registerViews(const std::vector<ViewCloud>& views,
                                          const ViewRegistrationParams& params = {});

}  // namespace meadow::capture
