#pragma once
// Shader programs built from the files under shaders/ (embedded in the binary at build time).
// Every stage gets "#version 450 core", the host defines, and gpu/Bindings.h prepended; "#include"
// lines are resolved against shaders/. Compile and link errors name the shader file and line.
#include "core/Error.h"
#include "gpu/Handle.h"

#include <glm/mat4x4.hpp>

#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace bounce::gl {

struct ProgramDesc {
    std::string label;
    // (stage, file relative to shaders/), e.g. {GL_VERTEX_SHADER, "render/gbuffer.vert"}
    std::vector<std::pair<GLenum, std::string>> stages;
    std::vector<std::pair<std::string, std::string>> defines;  // #define NAME VALUE
    std::vector<std::string> feedbackVaryings;                // transform feedback outputs, interleaved
};

class Program {
public:
    Program() = default;
    static Expected<Program> build(const ProgramDesc& desc);

    void use() const { glUseProgram(m_handle.id()); }
    GLuint id() const { return m_handle.id(); }
    const std::string& label() const { return m_label; }
    explicit operator bool() const { return static_cast<bool>(m_handle); }

    // Uniform setters for the few per-draw values not in uniform blocks. Unknown names are ignored
    // (the compiler may remove unused uniforms) but logged once at debug level.
    void set(std::string_view name, int v);
    void set(std::string_view name, unsigned v);
    void set(std::string_view name, float v);
    void set(std::string_view name, const glm::vec2& v);
    void set(std::string_view name, const glm::vec3& v);
    void set(std::string_view name, const glm::vec4& v);
    void set(std::string_view name, const glm::ivec2& v);
    void set(std::string_view name, const glm::mat4& v);
    // A uniform array from its element 0 (GLSL `uniform int name[N]` / `ivec2 name[N]`; at most N values).
    void set(std::string_view name, const std::vector<int>& v);
    void set(std::string_view name, const std::vector<glm::ivec2>& v);

    // Compute dispatch helper: groups = ceil(size / localSize).
    static void dispatch(int sizeX, int sizeY, int sizeZ, int localX, int localY = 1, int localZ = 1);

private:
    GLint location(std::string_view name);

    Handle<ProgramTraits> m_handle;
    std::string m_label;
    std::unordered_map<std::string, GLint> m_locations;
};

// The preprocessed source of one shader file (includes resolved), for tests and error messages.
Expected<std::string> preprocessShader(const std::string& file,
                                       const std::vector<std::pair<std::string, std::string>>& defines);

}  // namespace bounce::gl
