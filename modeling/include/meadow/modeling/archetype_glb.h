#pragma once
// glTF 2.0 binary export of an archetype library, for DCC tools: one mesh per archetype (its
// ribbon from blade_mesh.h: metres, +Y up, normals, the width profile shaped into the mesh), one
// node per mesh laid out side by side along +X, and the archetype's name, height, width profile,
// nearest shape, fit report and source in the node's `extras`.
#include <filesystem>
#include <string>

#include "meadow/modeling/archetype_library.h"

namespace meadow::modeling {

struct GlbExportOptions {
    int segmentsPerBlade = 16;  // ribbon quads along each spine
    float nodeSpacing_m = 0.f;  // gap between archetypes along +X; 0 = 1.5 x widest extent
};

// Written atomically; throws ModelingError on an empty library or an unwritable path.
void exportArchetypeGlb(const ArchetypeLibrary& library, const std::filesystem::path& glbPath,
                        const GlbExportOptions& options = {});

// The same document as bytes (the exporter writes these).
std::string archetypeGlbBytes(const ArchetypeLibrary& library,
                              const GlbExportOptions& options = {});

// Whether `path` is a glTF binary that meadow wrote (its asset generator names meadow): what a
// capture may replace. False for anything unreadable.
bool isMeadowGlb(const std::filesystem::path& path);

}  // namespace meadow::modeling
