#pragma once
// The one owner of a GL object name. Move-only; moves swap, so a moved-over handle's old object is
// deleted by the moved-from temporary (the Tungsten leak cannot happen). Only Traits::destroy calls
// glDelete*.
#include <epoxy/gl.h>

#include <utility>

namespace bounce::gl {

template <class Traits>
class Handle {
public:
    Handle() noexcept = default;
    explicit Handle(GLuint id) noexcept : m_id(id) {}
    Handle(Handle&& other) noexcept : m_id(std::exchange(other.m_id, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        std::swap(m_id, other.m_id);
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    ~Handle() {
        if (m_id != 0) Traits::destroy(m_id);
    }

    GLuint id() const noexcept { return m_id; }
    explicit operator bool() const noexcept { return m_id != 0; }
    GLuint release() noexcept { return std::exchange(m_id, 0); }

private:
    GLuint m_id = 0;
};

struct BufferTraits { static void destroy(GLuint id) { glDeleteBuffers(1, &id); } };
struct TextureTraits { static void destroy(GLuint id) { glDeleteTextures(1, &id); } };
struct FramebufferTraits { static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); } };
struct VertexArrayTraits { static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); } };
struct ProgramTraits { static void destroy(GLuint id) { glDeleteProgram(id); } };
struct ShaderTraits { static void destroy(GLuint id) { glDeleteShader(id); } };
struct QueryTraits { static void destroy(GLuint id) { glDeleteQueries(1, &id); } };
struct SamplerTraits { static void destroy(GLuint id) { glDeleteSamplers(1, &id); } };
struct TransformFeedbackTraits { static void destroy(GLuint id) { glDeleteTransformFeedbacks(1, &id); } };

}  // namespace bounce::gl
