#include "shader_sources.h"

#include "meadow/runtime/error.h"

namespace meadow::runtime::detail {

std::string_view shaderSource(std::string_view relativePath) {
    for (const auto& [path, text] : embeddedShaders())
        if (path == relativePath) return text;
    throw Error("meadow::runtime: no embedded shader named '" + std::string(relativePath) +
                "' (is it under shaders/ and was the build re-run?)");
}

}  // namespace meadow::runtime::detail
