#pragma once
// The truth folder `meadow synth` writes beside a recording (truth/ with a truth file and
// labels/NNNNNN.png), shared by the tuft presets (blades.json) and scanned plants (plant.json).
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>

namespace meadow::synth::detail {

inline constexpr const char* kTruthFolderName = "truth";
inline constexpr const char* kLabelsFolderName = "labels";

// "labels/000012.png": frame 12's label image, relative to the truth folder.
[[nodiscard]] std::string labelsPath(int frameIndex);

// A 16-bit label image as PNG, written atomically. Throws SynthError.
void writeLabels(const std::filesystem::path& file, const cv::Mat1w& labels);

// Throws SynthError saying why `out` may not be replaced: it holds something that is not a meadow
// recording with a synth truth folder (which meadow synth would then delete).
void checkReplaceableSynthOutput(const std::filesystem::path& out);

}  // namespace meadow::synth::detail
