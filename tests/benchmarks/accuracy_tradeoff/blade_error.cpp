// A tuft's capture scored against the truth (blade_error.h).
#include "accuracy_tradeoff/blade_error.h"

namespace meadow::bench {

TuftScore scoreCapture(const Scene& scene, const TuftCapture& cap) {
    TuftScore s;
    const BladeMatch m = matchBlades(scene.labels, cap.segmentation.blades);
    s.trueBlades = static_cast<int>(m.trueIds.size());
    s.found = static_cast<int>(cap.segmentation.blades.size());
    s.fitFailures = cap.fitFailures;
    s.iou = m.trueBestIou;
    for (std::size_t b = 0; b < cap.fits.size(); ++b) {
        if (!cap.fits[b]) continue;
        ++s.fitted;
        const int id = m.foundToTrueId[b];
        if (id == 0) continue;
        ++s.fittedMatched;
        s.errors.push_back(
            bladeError(*cap.fits[b], scene.tuft.blades.at(static_cast<std::size_t>(id - 1))));
        s.matchedFits.push_back(&*cap.fits[b]);
    }
    return s;
}

}  // namespace meadow::bench
