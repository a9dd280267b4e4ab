#pragma once
// GLSL sources from shaders/, embedded at build time by cmake/EmbedShaders.cmake.
#include <string_view>
#include <utility>
#include <vector>

namespace meadow::runtime::detail {

const std::vector<std::pair<std::string_view, std::string_view>>& embeddedShaders();
// Text of shaders/<relativePath>; throws meadow::Error if there is no such file.
std::string_view shaderSource(std::string_view relativePath);

}  // namespace meadow::runtime::detail
