#include "gpu/Objects.h"

#include "core/Check.h"

#include <spdlog/spdlog.h>

#include <string>

namespace bounce::gl {

void label(GLenum identifier, GLuint id, std::string_view name) {
    if (!name.empty()) glObjectLabel(identifier, id, static_cast<GLsizei>(name.size()), name.data());
}

Buffer Buffer::create(std::string_view name, size_t bytes, const void* data, GLbitfield flags) {
    BOUNCE_CHECK(bytes > 0, "buffer '{}' of zero size", name);
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer b;
    b.m_handle = Handle<BufferTraits>(id);
    b.m_size = bytes;
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
    label(GL_BUFFER, id, name);
    return b;
}

void Buffer::upload(size_t offset, size_t bytes, const void* data) {
    BOUNCE_CHECK(offset + bytes <= m_size, "upload of {} bytes at {} overflows buffer of {}", bytes, offset, m_size);
    if (bytes > 0) glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void Buffer::clearZero() { glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr); }

void Buffer::bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }

void Buffer::bindRange(GLenum target, GLuint index, size_t offset, size_t bytes) const {
    glBindBufferRange(target, index, id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes));
}

void Buffer::download(size_t offset, size_t bytes, void* out) const {
    BOUNCE_CHECK(offset + bytes <= m_size, "download overflows buffer");
    glGetNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

Texture Texture::create(std::string_view name, const TextureDesc& desc) {
    BOUNCE_CHECK(desc.width > 0 && desc.height > 0 && desc.depth > 0 && desc.levels > 0, "texture '{}' has size {}x{}x{}",
                 name, desc.width, desc.height, desc.depth);
    GLuint id = 0;
    glCreateTextures(desc.target, 1, &id);
    Texture t;
    t.m_handle = Handle<TextureTraits>(id);
    t.m_desc = desc;
    switch (desc.target) {
        case GL_TEXTURE_2D:
        case GL_TEXTURE_CUBE_MAP:
            glTextureStorage2D(id, desc.levels, desc.format, desc.width, desc.height);
            break;
        case GL_TEXTURE_2D_ARRAY:
        case GL_TEXTURE_CUBE_MAP_ARRAY:
        case GL_TEXTURE_3D:
            glTextureStorage3D(id, desc.levels, desc.format, desc.width, desc.height, desc.depth);
            break;
        case GL_TEXTURE_2D_MULTISAMPLE:
            glTextureStorage2DMultisample(id, desc.samples, desc.format, desc.width, desc.height, GL_TRUE);
            label(GL_TEXTURE, id, name);
            return t;
        case GL_TEXTURE_2D_MULTISAMPLE_ARRAY:
            // Multisampled textures have no sampler state: setting filters on them is an error.
            glTextureStorage3DMultisample(id, desc.samples, desc.format, desc.width, desc.height, desc.depth, GL_TRUE);
            label(GL_TEXTURE, id, name);
            return t;
        default: BOUNCE_CHECK(false, "texture '{}': unsupported target 0x{:x}", name, desc.target);
    }
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(desc.minFilter));
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(desc.magFilter));
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(desc.wrap));
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(desc.wrap));
    glTextureParameteri(id, GL_TEXTURE_WRAP_R, static_cast<GLint>(desc.wrap));
    label(GL_TEXTURE, id, name);
    return t;
}

Texture Texture::create2D(std::string_view name, int width, int height, GLenum format, int levels) {
    TextureDesc d;
    d.width = width;
    d.height = height;
    d.format = format;
    d.levels = levels;
    if (levels > 1) d.minFilter = GL_LINEAR_MIPMAP_LINEAR;
    return create(name, d);
}

void Texture::bindImage(GLuint unit, GLenum access, int level, bool layered, int layer) const {
    glBindImageTexture(unit, id(), level, layered ? GL_TRUE : GL_FALSE, layer, access, m_desc.format);
}

void Texture::setCompareMode(bool enabled) {
    glTextureParameteri(id(), GL_TEXTURE_COMPARE_MODE, enabled ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
    glTextureParameteri(id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

void Texture::setFilter(GLenum minFilter, GLenum magFilter) {
    glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
    glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(magFilter));
    m_desc.minFilter = minFilter;
    m_desc.magFilter = magFilter;
}

Framebuffer Framebuffer::create(std::string_view name) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    Framebuffer f;
    f.m_handle = Handle<FramebufferTraits>(id);
    f.m_name = name;
    label(GL_FRAMEBUFFER, id, name);
    return f;
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int level) {
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}

void Framebuffer::attachLayer(GLenum attachment, const Texture& texture, int layer, int level) {
    glNamedFramebufferTextureLayer(id(), attachment, texture.id(), level, layer);
}

void Framebuffer::setDrawBuffers(int colorCount) {
    GLenum buffers[8];
    BOUNCE_CHECK(colorCount >= 0 && colorCount <= 8, "{} draw buffers", colorCount);
    for (int i = 0; i < colorCount; ++i) buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    if (colorCount == 0)
        glNamedFramebufferDrawBuffer(id(), GL_NONE);
    else
        glNamedFramebufferDrawBuffers(id(), colorCount, buffers);
}

bool Framebuffer::complete() const {
    const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        spdlog::error("framebuffer '{}' incomplete: 0x{:x}", m_name, status);
        return false;
    }
    return true;
}

VertexArray VertexArray::create(std::string_view name) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    VertexArray v;
    v.m_handle = Handle<VertexArrayTraits>(id);
    label(GL_VERTEX_ARRAY, id, name);
    return v;
}

TransformFeedback TransformFeedback::create(std::string_view name) {
    GLuint id = 0;
    glCreateTransformFeedbacks(1, &id);
    TransformFeedback t;
    t.m_handle = Handle<TransformFeedbackTraits>(id);
    label(GL_TRANSFORM_FEEDBACK, id, name);
    return t;
}

Query Query::create(std::string_view name, GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    Query q;
    q.m_handle = Handle<QueryTraits>(id);
    label(GL_QUERY, id, name);
    return q;
}

}  // namespace bounce::gl
