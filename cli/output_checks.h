#pragma once
// What a verb may overwrite: checked before any work starts, so a refusal costs nothing and
// touches nothing. A verb replaces only outputs of its own kind (a library, a .glb, a render
// folder, capture overlays), never a file or folder of the user's, and never its own input.
#include <filesystem>
#include <functional>
#include <string>

namespace meadow::cli {

// Both paths name the same file (after following links and "..").
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws meadow::Error when `path` exists and is a folder, or a file `isOurs` does not accept:
// "refusing to overwrite PATH (OPTION): WHY; choose another path or remove it first".
void refuseToReplace(const std::filesystem::path& path, const std::string& option,
                     const std::function<bool(const std::filesystem::path&)>& isOurs,
                     const std::string& why);

// The same for a folder of outputs: it may be absent or empty, or hold only entries whose
// names `isOurs` accepts (and their temporaries).
void refuseFolderOfOthers(const std::filesystem::path& folder, const std::string& option,
                          const std::function<bool(const std::string& name)>& isOurs,
                          const std::string& why);

// Capture's overlays: frame_NNNNNN.png.
bool isOverlayName(const std::string& name);

}  // namespace meadow::cli
