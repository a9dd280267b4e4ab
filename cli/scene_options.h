#pragma once
// The options a rendering verb applies to a scene file: --library replaces its archetypes,
// --size its image size.
#include <string>

#include "meadow/runtime/scene.h"

namespace meadow::cli {

// Loads `scene`; a non-empty `library` replaces its archetypes (each equally likely), a
// non-empty `size` ("WIDTHxHEIGHT") its render size. Errors name `verb`. Throws meadow::Error.
runtime::SceneDescription loadSceneWithOptions(const std::string& verb, const std::string& scene,
                                               const std::string& library, const std::string& size);

}  // namespace meadow::cli
