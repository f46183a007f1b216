#pragma once
// The one owner of a GL object name. Move-only; moves swap, so a moved-over handle's old object is
// deleted by the moved-from temporary (the Tungsten leak cannot happen). Only Traits::destroy calls
// glDelete*. Every handle is counted in the live-object ledger (liveResources() in gpu/Objects.h).
#include <epoxy/gl.h>

#include <cstdint>
#include <utility>

namespace bounce::gl {

enum class ObjectKind { Buffer, Texture, Framebuffer, VertexArray, Program, Shader, Query, Sampler, TransformFeedback, Count };

// The live-object ledger behind liveResources() (gpu/Objects.h): every Handle reports its object's
// creation and deletion; Buffer and Texture also report their storage bytes.
namespace ledger {
void created(ObjectKind kind, GLuint id);
void deleted(ObjectKind kind, GLuint id);
void storage(ObjectKind kind, GLuint id, uint64_t bytes);
}  // namespace ledger

template <class Traits>
class Handle {
public:
    Handle() noexcept = default;
    explicit Handle(GLuint id) noexcept : m_id(id) {
        if (m_id != 0) ledger::created(Traits::kKind, m_id);
    }
    Handle(Handle&& other) noexcept : m_id(std::exchange(other.m_id, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        std::swap(m_id, other.m_id);
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    ~Handle() {
        if (m_id != 0) {
            ledger::deleted(Traits::kKind, m_id);
            Traits::destroy(m_id);
        }
    }

    GLuint id() const noexcept { return m_id; }
    explicit operator bool() const noexcept { return m_id != 0; }
    // The object leaves the wrappers (and the ledger): the caller deletes it.
    GLuint release() noexcept {
        if (m_id != 0) ledger::deleted(Traits::kKind, m_id);
        return std::exchange(m_id, 0);
    }

private:
    GLuint m_id = 0;
};

struct BufferTraits { static constexpr ObjectKind kKind = ObjectKind::Buffer; static void destroy(GLuint id) { glDeleteBuffers(1, &id); } };
struct TextureTraits { static constexpr ObjectKind kKind = ObjectKind::Texture; static void destroy(GLuint id) { glDeleteTextures(1, &id); } };
struct FramebufferTraits { static constexpr ObjectKind kKind = ObjectKind::Framebuffer; static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); } };
struct VertexArrayTraits { static constexpr ObjectKind kKind = ObjectKind::VertexArray; static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); } };
struct ProgramTraits { static constexpr ObjectKind kKind = ObjectKind::Program; static void destroy(GLuint id) { glDeleteProgram(id); } };
struct ShaderTraits { static constexpr ObjectKind kKind = ObjectKind::Shader; static void destroy(GLuint id) { glDeleteShader(id); } };
struct QueryTraits { static constexpr ObjectKind kKind = ObjectKind::Query; static void destroy(GLuint id) { glDeleteQueries(1, &id); } };
struct SamplerTraits { static constexpr ObjectKind kKind = ObjectKind::Sampler; static void destroy(GLuint id) { glDeleteSamplers(1, &id); } };
struct TransformFeedbackTraits { static constexpr ObjectKind kKind = ObjectKind::TransformFeedback; static void destroy(GLuint id) { glDeleteTransformFeedbacks(1, &id); } };

}  // namespace bounce::gl
