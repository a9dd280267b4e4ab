#pragma once
// GLSL programs from the sources embedded at build time (shader_sources.h). Core GLSL 4.50 has
// no #include, so each stage's text is assembled as
//     #version 450 core
//     #define NAME VALUE            (generated from C++)
//     shared/blade_types.h          (compiles as GLSL and C++)
//     common_*.glsl                 (the ones the program names, in order)
//     the stage file
// with a `#line 1 N` before each part, N numbering the parts, so a driver's "N:line" in a log
// points at the right file; the error message lists which file each N is.
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "gl_object.h"

namespace meadow::runtime::gl {

struct ShaderDefine {
    std::string name;
    std::string value;
};

struct ShaderStageFile {
    GLenum stage;      // GL_VERTEX_SHADER, GL_TESS_CONTROL_SHADER, ..., GL_COMPUTE_SHADER
    std::string file;  // relative to shaders/, e.g. "blade.vert"
};

struct ProgramSource {
    std::string label;  // for messages, e.g. "blade draw"
    std::vector<ShaderStageFile> stages;
    std::vector<std::string> commonFiles;  // relative to shaders/, e.g. "common_bezier.glsl"
    std::vector<ShaderDefine> defines;
};

// The relative path of the shared header every program starts with.
inline constexpr std::string_view kSharedTypesFile = "shared/blade_types.h";

// The full text of one stage as it goes to the driver; `partNames` receives the file of each
// `#line` source number. Throws meadow::Error when a file is not embedded.
std::string assembleStageSource(const ProgramSource& program, const ShaderStageFile& stage,
                                std::vector<std::string>* partNames = nullptr);

class ShaderProgram {
public:
    // Compiles and links; throws RuntimeError naming the shader file and the driver's log.
    explicit ShaderProgram(const ProgramSource& source);

    [[nodiscard]] const Program& program() const { return program_; }
    [[nodiscard]] const std::string& label() const { return label_; }
    void use() const;

    // Uniform location, -1 when the name is absent (or optimised away).
    [[nodiscard]] GLint location(const char* name) const;
    void set(const char* name, float value) const;
    void set(const char* name, int value) const;
    void set(const char* name, unsigned value) const;
    void set(const char* name, glm::vec2 value) const;
    void set(const char* name, glm::vec3 value) const;
    void set(const char* name, glm::vec4 value) const;
    void set(const char* name, const glm::mat4& value) const;

private:
    Program program_;
    std::string label_;
};

}  // namespace meadow::runtime::gl
