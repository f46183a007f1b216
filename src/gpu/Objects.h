#pragma once
// Move-only RAII GL objects over DSA (glCreate*), each with a debug label (glObjectLabel) so that
// debug output and frame debuggers name them ("gbuffer.normal", "rsm.flux").
#include "gpu/Handle.h"

#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace bounce::gl {

void label(GLenum identifier, GLuint id, std::string_view name);

// What the wrappers hold now, across every context of the process: live GL objects of each kind and
// the bytes of buffer and texture storage (immutable storage, so the bytes are exact for buffers and
// the formats' texel sizes for textures). Run records carry it per frame (`resources`), the soak
// benchmark and test check it stays flat (bench/soak/run.py, tests/cli/soak_test.py).
struct LiveResources {
    int64_t objects = 0;  // every kind together
    int64_t buffers = 0, textures = 0, framebuffers = 0, vertexArrays = 0, programs = 0, shaders = 0, queries = 0;
    uint64_t bufferBytes = 0, textureBytes = 0;
};
LiveResources liveResources();
// Bytes of one texel of a sized internal format (GL_RGBA16F: 8).
uint64_t texelBytes(GLenum internalFormat);
// Bytes of a texture's storage: every level, layer and sample.
uint64_t textureStorageBytes(const struct TextureDesc& desc);

class Buffer {
public:
    Buffer() = default;
    // Immutable storage (glNamedBufferStorage). Flags default to updatable with glNamedBufferSubData.
    static Buffer create(std::string_view name, size_t bytes, const void* data = nullptr,
                         GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    void upload(size_t offset, size_t bytes, const void* data);
    void clearZero();
    void bindBase(GLenum target, GLuint index) const;
    void bindRange(GLenum target, GLuint index, size_t offset, size_t bytes) const;
    // Reads back `bytes` from `offset` (synchronous; tests and CPU-side techniques).
    void download(size_t offset, size_t bytes, void* out) const;
    GLuint id() const { return m_handle.id(); }
    size_t size() const { return m_size; }
    explicit operator bool() const { return static_cast<bool>(m_handle); }

private:
    Handle<BufferTraits> m_handle;
    size_t m_size = 0;
};

struct TextureDesc {
    GLenum target = GL_TEXTURE_2D;
    GLenum format = GL_RGBA16F;  // sized internal format
    int width = 1, height = 1, depth = 1;  // depth = layers for arrays (x6 for cube arrays), slices for 3D
    int levels = 1;
    GLenum minFilter = GL_LINEAR, magFilter = GL_LINEAR;
    GLenum wrap = GL_CLAMP_TO_EDGE;
    int samples = 0;  // GL_TEXTURE_2D_MULTISAMPLE(_ARRAY) only: samples per texel (no sampler state)
};

class Texture {
public:
    Texture() = default;
    static Texture create(std::string_view name, const TextureDesc& desc);
    static Texture create2D(std::string_view name, int width, int height, GLenum format, int levels = 1);
    // A GL_TEXTURE_2D_ARRAY of `layers` layers sampled with `filter` (magnification; minification too,
    // with the nearest mip level when levels > 1).
    static Texture create2DArray(std::string_view name, int width, int height, int layers, GLenum format, int levels = 1,
                                 GLenum filter = GL_NEAREST);
    // A buffer texture (samplerBuffer) over all of `buffer`, read as `format` texels: its storage is the
    // buffer's (counted there), so the buffer must outlive the view.
    static Texture createBufferView(std::string_view name, const Buffer& buffer, GLenum format);
    // A view of all of `source` (immutable storage, one layer or 2D) read as `format`, a format of the
    // same view class (GL 4.3 texture views: R32F as R32UI for image atomics). Its storage is the
    // source's (counted there), so the source must outlive the view.
    static Texture createView(std::string_view name, const Texture& source, GLenum format);
    void bind(GLuint unit) const { glBindTextureUnit(unit, m_handle.id()); }
    void bindImage(GLuint unit, GLenum access, int level = 0, bool layered = false, int layer = 0) const;
    // Depth-compare sampling (sampler2DShadow / samplerCubeShadow).
    void setCompareMode(bool enabled);
    void setFilter(GLenum minFilter, GLenum magFilter);
    void generateMipmaps() { glGenerateTextureMipmap(m_handle.id()); }
    GLuint id() const { return m_handle.id(); }
    const TextureDesc& desc() const { return m_desc; }
    int width() const { return m_desc.width; }
    int height() const { return m_desc.height; }
    explicit operator bool() const { return static_cast<bool>(m_handle); }

private:
    Handle<TextureTraits> m_handle;
    TextureDesc m_desc;
};

class Framebuffer {
public:
    Framebuffer() = default;
    static Framebuffer create(std::string_view name);
    void attach(GLenum attachment, const Texture& texture, int level = 0);
    void attachLayer(GLenum attachment, const Texture& texture, int layer, int level = 0);
    void setDrawBuffers(int colorCount);
    // Returns false (and logs) when incomplete; callers treat that as a bug (BOUNCE_CHECK).
    bool complete() const;
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, m_handle.id()); }
    GLuint id() const { return m_handle.id(); }

private:
    Handle<FramebufferTraits> m_handle;
    std::string_view m_name;
};

class VertexArray {
public:
    VertexArray() = default;
    static VertexArray create(std::string_view name);
    void bind() const { glBindVertexArray(m_handle.id()); }
    GLuint id() const { return m_handle.id(); }

private:
    Handle<VertexArrayTraits> m_handle;
};

class TransformFeedback {
public:
    TransformFeedback() = default;
    static TransformFeedback create(std::string_view name);
    GLuint id() const { return m_handle.id(); }

private:
    Handle<TransformFeedbackTraits> m_handle;
};

class Query {
public:
    Query() = default;
    static Query create(std::string_view name, GLenum target);
    GLuint id() const { return m_handle.id(); }

private:
    Handle<QueryTraits> m_handle;
};

}  // namespace bounce::gl
