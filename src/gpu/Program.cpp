#include "gpu/Program.h"
#include "gpu/ShaderLog.h"

#include "core/Check.h"
#include "core/FileIo.h"
#include "gpu/Objects.h"
#include "gpu/ProgramChecks.h"

#include <glm/gtc/type_ptr.hpp>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <span>
#include <sstream>

namespace bounce::gl {

std::span<const std::pair<std::string_view, std::string_view>> embeddedShaderFiles();

namespace {

// BOUNCE_SHADER_DIR lets a developer edit shaders without rebuilding; otherwise the embedded copy.
Expected<std::string> shaderFileText(const std::string& file) {
    if (const char* dir = std::getenv("BOUNCE_SHADER_DIR")) {
        const std::filesystem::path p = file == "Bindings.h" ? std::filesystem::path(dir) / "../src/gpu/Bindings.h"
                                                             : std::filesystem::path(dir) / file;
        return readTextFile(p);
    }
    for (const auto& [name, text] : embeddedShaderFiles())
        if (name == file) return std::string(text);
    return makeError("shader file '{}' not found under shaders/", file);
}


void appendLine(std::string& out, std::vector<LineOrigin>& origins, const std::string& text, const std::string& file,
                int line) {
    out += text;
    out += '\n';
    origins.push_back({file, line});
}

// Resolves #include "x" recursively (paths relative to shaders/).
Expected<void> expand(const std::string& file, std::vector<LineOrigin>& origins, std::string& out, int depth) {
    if (depth > 16) return makeError("{}: #include nested too deeply (cycle?)", file);
    BOUNCE_TRY(std::string text, shaderFileText(file));
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    static const std::regex includeRe(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    while (std::getline(in, line)) {
        ++lineNo;
        std::smatch m;
        if (std::regex_match(line, m, includeRe)) {
            auto r = expand(m[1].str(), origins, out, depth + 1);
            if (!r.ok()) return makeError("{}:{}: {}", file, lineNo, r.error().message);
        } else {
            appendLine(out, origins, line, file, lineNo);
        }
    }
    return {};
}

Expected<std::string> assemble(const std::string& file, const std::vector<std::pair<std::string, std::string>>& defines,
                               std::vector<LineOrigin>& origins) {
    std::string src;
    appendLine(src, origins, "#version 450 core", "(prelude)", 1);
    for (const auto& [name, value] : defines)
        appendLine(src, origins, fmt::format("#define {} {}", name, value), "(host define)", 1);
    // Bindings.h first, so binding indices are shared with C++.
    BOUNCE_TRY_VOID(expand("Bindings.h", origins, src, 0));
    BOUNCE_TRY_VOID(expand(file, origins, src, 0));
    return src;
}

const char* stageName(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER: return "vertex";
        case GL_GEOMETRY_SHADER: return "geometry";
        case GL_FRAGMENT_SHADER: return "fragment";
        case GL_COMPUTE_SHADER: return "compute";
        case GL_TESS_CONTROL_SHADER: return "tess-control";
        case GL_TESS_EVALUATION_SHADER: return "tess-evaluation";
        default: return "unknown";
    }
}

}  // namespace

Expected<std::string> preprocessShader(const std::string& file, const std::vector<std::pair<std::string, std::string>>& defines) {
    std::vector<LineOrigin> origins;
    return assemble(file, defines, origins);
}

Expected<Program> Program::build(const ProgramDesc& desc) {
    BOUNCE_CHECK(!desc.stages.empty(), "program '{}' has no stages", desc.label);
    GLuint program = glCreateProgram();
    Program p;
    p.m_handle = Handle<ProgramTraits>(program);
    p.m_label = desc.label;
    std::vector<Handle<ShaderTraits>> shaders;
    std::vector<StageSource> sources;
    for (const auto& [stage, file] : desc.stages) {
        std::vector<LineOrigin> origins;
        auto source = assemble(file, desc.defines, origins);
        if (!source.ok()) return makeError("program '{}': {}", desc.label, source.error().message);
        sources.push_back({stage, file, *source});
        GLuint shader = glCreateShader(stage);
        shaders.emplace_back(shader);
        const char* text = source->c_str();
        glShaderSource(shader, 1, &text, nullptr);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint length = 0;
            glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
            std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
            glGetShaderInfoLog(shader, length, nullptr, log.data());
            return makeError("program '{}': {} shader {} failed to compile:\n{}", desc.label, stageName(stage), file,
                             mapShaderLog(log, origins));
        }
        glAttachShader(program, shader);
    }
    if (!desc.feedbackVaryings.empty()) {
        std::vector<const char*> names;
        for (const auto& v : desc.feedbackVaryings) names.push_back(v.c_str());
        glTransformFeedbackVaryings(program, static_cast<GLsizei>(names.size()), names.data(), GL_INTERLEAVED_ATTRIBS);
    }
    dumpShaderSources(desc.label, sources);
    glLinkProgram(program);
    for (auto& s : shaders) glDetachShader(program, s.id());
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
        return makeError("program '{}' failed to link: {}", desc.label, log);
    }
    // Past a portable limit (gpu/PortableLimits.h) under BOUNCE_PORTABLE_LIMITS=1 this fails as a link would.
    BOUNCE_TRY_VOID(auditLinkedProgram(desc.label, program, sources));
    gl::label(GL_PROGRAM, program, desc.label);
    return p;
}

GLint Program::location(std::string_view name) {
    auto it = m_locations.find(std::string(name));
    if (it != m_locations.end()) return it->second;
    const std::string key(name);
    const GLint loc = glGetUniformLocation(id(), key.c_str());
    if (loc < 0) spdlog::debug("program '{}': uniform '{}' not active", m_label, key);
    m_locations.emplace(key, loc);
    return loc;
}

void Program::set(std::string_view n, int v) { glProgramUniform1i(id(), location(n), v); }
void Program::set(std::string_view n, unsigned v) { glProgramUniform1ui(id(), location(n), v); }
void Program::set(std::string_view n, float v) { glProgramUniform1f(id(), location(n), v); }
void Program::set(std::string_view n, const glm::vec2& v) { glProgramUniform2fv(id(), location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::vec3& v) { glProgramUniform3fv(id(), location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::vec4& v) { glProgramUniform4fv(id(), location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::ivec2& v) { glProgramUniform2iv(id(), location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::mat4& v) {
    glProgramUniformMatrix4fv(id(), location(n), 1, GL_FALSE, glm::value_ptr(v));
}

void Program::set(std::string_view n, const std::vector<int>& v) {
    glProgramUniform1iv(id(), location(n), static_cast<GLsizei>(v.size()), v.data());
}
void Program::set(std::string_view n, const std::vector<glm::ivec2>& v) {
    glProgramUniform2iv(id(), location(n), static_cast<GLsizei>(v.size()), glm::value_ptr(v.front()));
}

void Program::dispatch(int sx, int sy, int sz, int lx, int ly, int lz) {
    auto groups = [](int size, int local) { return static_cast<GLuint>((size + local - 1) / local); };
    glDispatchCompute(groups(sx, lx), groups(sy, ly), groups(sz, lz));
}

}  // namespace bounce::gl
