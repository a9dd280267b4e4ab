#include "scene_options.h"

#include <cstdio>

#include "meadow/modeling/archetype_library.h"
#include "meadow/runtime/error.h"

namespace meadow::cli {

runtime::SceneDescription loadSceneWithOptions(const std::string& verb,
                                               const std::string& scenePath,
                                               const std::string& library,
                                               const std::string& size) {
    constexpr int kMaxSide_px = 16384;
    runtime::SceneDescription scene = runtime::loadSceneDescription(scenePath);
    if (!library.empty()) {
        // The scene's weights name the archetypes it was written for, so a captured library
        // plants each of its archetypes equally often.
        scene.archetypes = modeling::loadArchetypeLibrary(library).archetypes;
        scene.archetypeWeights.assign(scene.archetypes.size(), 1.f);
    }
    if (!size.empty()) {
        int w = 0, h = 0;
        char x = 0, extra = 0;
        if (std::sscanf(size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 ||
            (x != 'x' && x != 'X') || w < 1 || h < 1 || w > kMaxSide_px || h > kMaxSide_px)
            throw runtime::RuntimeError(verb + ": --size '" + size +
                                        "' is not WIDTHxHEIGHT in pixels (e.g. 1280x720)");
        scene.render.width_px = w;
        scene.render.height_px = h;
    }
    return scene;
}

}  // namespace meadow::cli
