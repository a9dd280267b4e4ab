#include "gl/shader_program.h"

#include <algorithm>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

#include "meadow/runtime/error.h"
#include "shader_sources.h"

namespace meadow::runtime::gl {
namespace {

const char* stageName(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_TESS_CONTROL_SHADER:
            return "tessellation control";
        case GL_TESS_EVALUATION_SHADER:
            return "tessellation evaluation";
        case GL_GEOMETRY_SHADER:
            return "geometry";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        case GL_COMPUTE_SHADER:
            return "compute";
        default:
            return "unknown";
    }
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    return log;
}

std::string programLog(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    return log;
}

// The log on one line, so the CLI can print the error as a single line.
std::string oneLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    for (char& c : text)
        if (c == '\n') c = ';';
    return text;
}

std::string legend(const std::vector<std::string>& partNames) {
    std::string s;
    for (std::size_t i = 0; i < partNames.size(); ++i)
        s += (i ? ", " : "") + std::to_string(i) + "=shaders/" + partNames[i];
    return s;
}

}  // namespace

std::string assembleStageSource(const ProgramSource& program, const ShaderStageFile& stage,
                                std::vector<std::string>* partNames) {
    std::string text = "#version 450 core\n";
    for (const ShaderDefine& d : program.defines)
        text += "#define " + d.name + " " + d.value + "\n";
    std::vector<std::string> parts;
    parts.emplace_back(kSharedTypesFile);
    for (const std::string& f : program.commonFiles) parts.push_back(f);
    parts.push_back(stage.file);
    for (std::size_t i = 0; i < parts.size(); ++i) {
        text += "#line 1 " + std::to_string(i) + "\n";
        text += detail::shaderSource(parts[i]);
        text += "\n";
    }
    if (partNames) *partNames = std::move(parts);
    return text;
}

ShaderProgram::ShaderProgram(const ProgramSource& source)
    : program_(Program::create()), label_(source.label) {
    std::vector<Shader> shaders;
    for (const ShaderStageFile& stage : source.stages) {
        std::vector<std::string> partNames;
        const std::string text = assembleStageSource(source, stage, &partNames);
        Shader shader = Shader::create(stage.stage);
        const char* ptr = text.c_str();
        glShaderSource(shader.id(), 1, &ptr, nullptr);
        glCompileShader(shader.id());
        GLint ok = GL_FALSE;
        glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
        if (!ok)
            throw RuntimeError("meadow::runtime: " + std::string(stageName(stage.stage)) +
                               " shader shaders/" + stage.file + " of program '" + label_ +
                               "' does not compile: " + oneLine(shaderLog(shader.id())) +
                               " (source numbers: " + legend(partNames) +
                               "); fix the GLSL and rebuild");
        glAttachShader(program_.id(), shader.id());
        shaders.push_back(std::move(shader));
    }
    glLinkProgram(program_.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program_.id(), GL_LINK_STATUS, &ok);
    std::string files;
    for (const ShaderStageFile& s : source.stages)
        files += (files.empty() ? "" : ", ") + ("shaders/" + s.file);
    for (const Shader& s : shaders) glDetachShader(program_.id(), s.id());
    if (!ok)
        throw RuntimeError("meadow::runtime: program '" + label_ + "' (" + files +
                           ") does not link: " + oneLine(programLog(program_.id())) +
                           "; fix the GLSL and rebuild");
}

void ShaderProgram::use() const { glUseProgram(program_.id()); }

GLint ShaderProgram::location(const char* name) const {
    return glGetUniformLocation(program_.id(), name);
}
void ShaderProgram::set(const char* name, float v) const {
    glProgramUniform1f(program_.id(), location(name), v);
}
void ShaderProgram::set(const char* name, int v) const {
    glProgramUniform1i(program_.id(), location(name), v);
}
void ShaderProgram::set(const char* name, unsigned v) const {
    glProgramUniform1ui(program_.id(), location(name), v);
}
void ShaderProgram::set(const char* name, glm::vec2 v) const {
    glProgramUniform2fv(program_.id(), location(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(const char* name, glm::vec3 v) const {
    glProgramUniform3fv(program_.id(), location(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(const char* name, glm::vec4 v) const {
    glProgramUniform4fv(program_.id(), location(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(const char* name, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(program_.id(), location(name), 1, GL_FALSE, glm::value_ptr(v));
}

}  // namespace meadow::runtime::gl
