#include "plant/stem_truth.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <vector>

namespace meadow::bench {

float truthStemHeight_m(const synth::PlantTruth& truth) {
    std::vector<float> heights;
    for (const synth::PlantTruthView& view : truth.views) {
        // The scanned plant's stem foot is the world's origin (docs/formats.md, "Plant truth").
        const glm::vec3 foot(view.cameraFromWorld * glm::vec4(0.f, 0.f, 0.f, 1.f));
        float highest = 0.f;
        for (const synth::PlantTruthOrgan& organ : view.organs)
            if (!organ.stem && !organ.centreLineCamera_m.empty())
                highest = std::max(highest, glm::length(organ.centreLineCamera_m.front() - foot));
        heights.push_back(highest);
    }
    if (heights.empty()) return 0.f;
    const auto middle = heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2);
    std::nth_element(heights.begin(), middle, heights.end());
    return *middle;
}

}  // namespace meadow::bench
