#include "gpu/Objects.h"

#include "core/Check.h"
#include "gpu/Context.h"
#include "gpu/MemoryCheck.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

namespace bounce::gl {

void label(GLenum identifier, GLuint id, std::string_view name) {
    if (!name.empty()) glObjectLabel(identifier, id, static_cast<GLsizei>(name.size()), name.data());
}

namespace {

// Object names are per context: the ledger keys storage by (context, name).
struct Ledger {
    std::mutex mutex;
    std::array<int64_t, static_cast<size_t>(ObjectKind::Count)> live{};
    std::map<std::tuple<const void*, ObjectKind, GLuint>, uint64_t> bytes;
    uint64_t bufferBytes = 0, textureBytes = 0;
};

Ledger& theLedger() {
    static Ledger ledger;
    return ledger;
}

uint64_t& bytesOf(Ledger& l, ObjectKind kind) { return kind == ObjectKind::Buffer ? l.bufferBytes : l.textureBytes; }

// A GL_OUT_OF_MEMORY from the allocation just made is an input problem (a size too large for this
// GPU), reported as one line by the CLI (app/Cli.cpp catches it) instead of an incomplete object.
void throwIfOutOfMemory(std::string_view what, std::string_view name, uint64_t bytes) {
    bool outOfMemory = false;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) outOfMemory |= e == GL_OUT_OF_MEMORY;
    if (outOfMemory) throw std::runtime_error(outOfMemoryMessage(what, name, bytes, true, std::nullopt));
}

// Video memory free as the driver reports it (gpu/MemoryCheck.h), nullopt without either extension
// (llvmpipe, Mesa's hardware drivers, Intel).
std::optional<uint64_t> freeVideoMemoryBytes() {
    constexpr GLenum kNvxCurrentAvailableKiB = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
    constexpr GLenum kAtiTextureFreeMemory = 0x87FC;    // GL_TEXTURE_FREE_MEMORY_ATI: 4 values, [0] total free KiB
    if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
        GLint kib = 0;
        glGetIntegerv(kNvxCurrentAvailableKiB, &kib);
        return static_cast<uint64_t>(kib) * 1024u;
    }
    if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
        GLint v[4] = {0, 0, 0, 0};
        glGetIntegerv(kAtiTextureFreeMemory, v);
        return static_cast<uint64_t>(v[0]) * 1024u;
    }
    return std::nullopt;
}

// Before an allocation: refuse one past the video memory the driver reports free (issue 29 #21).
void throwIfPastFreeMemory(std::string_view what, std::string_view name, uint64_t bytes) {
    const std::string m = outOfMemoryMessage(what, name, bytes, false, freeVideoMemoryBytes());
    if (!m.empty()) throw std::runtime_error(m);
}

}  // namespace

namespace ledger {

void created(ObjectKind kind, GLuint) {
    Ledger& l = theLedger();
    std::lock_guard lock(l.mutex);
    ++l.live[static_cast<size_t>(kind)];
}

void deleted(ObjectKind kind, GLuint id) {
    Ledger& l = theLedger();
    std::lock_guard lock(l.mutex);
    --l.live[static_cast<size_t>(kind)];
    if (kind != ObjectKind::Buffer && kind != ObjectKind::Texture) return;
    const auto it = l.bytes.find({Context::current(), kind, id});
    if (it == l.bytes.end()) return;
    bytesOf(l, kind) -= it->second;
    l.bytes.erase(it);
}

void storage(ObjectKind kind, GLuint id, uint64_t bytes) {
    Ledger& l = theLedger();
    std::lock_guard lock(l.mutex);
    uint64_t& entry = l.bytes[{Context::current(), kind, id}];
    bytesOf(l, kind) += bytes - entry;
    entry = bytes;
}

}  // namespace ledger

LiveResources liveResources() {
    Ledger& l = theLedger();
    std::lock_guard lock(l.mutex);
    LiveResources r;
    const auto live = [&](ObjectKind k) { return l.live[static_cast<size_t>(k)]; };
    for (int64_t n : l.live) r.objects += n;
    r.buffers = live(ObjectKind::Buffer);
    r.textures = live(ObjectKind::Texture);
    r.framebuffers = live(ObjectKind::Framebuffer);
    r.vertexArrays = live(ObjectKind::VertexArray);
    r.programs = live(ObjectKind::Program);
    r.shaders = live(ObjectKind::Shader);
    r.queries = live(ObjectKind::Query);
    r.bufferBytes = l.bufferBytes;
    r.textureBytes = l.textureBytes;
    return r;
}

uint64_t texelBytes(GLenum format) {
    switch (format) {
        case GL_R8: case GL_R8UI: case GL_R8I: case GL_STENCIL_INDEX8: return 1;
        case GL_RG8: case GL_R16F: case GL_R16UI: case GL_R16I: case GL_R16: case GL_DEPTH_COMPONENT16: return 2;
        case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_RG16F: case GL_RG16UI: case GL_RG16: case GL_R32F: case GL_R32UI:
        case GL_R32I: case GL_R11F_G11F_B10F: case GL_RGB10_A2: case GL_RGB9_E5: case GL_DEPTH_COMPONENT24:
        case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_RGBA8UI: case GL_RGBA8I: return 4;
        case GL_DEPTH32F_STENCIL8: case GL_RGBA16F: case GL_RGBA16UI: case GL_RGBA16: case GL_RG32F: case GL_RG32UI:
        case GL_RG32I: return 8;
        case GL_RGB32F: case GL_RGB32UI: return 12;
        case GL_RGBA32F: case GL_RGBA32UI: case GL_RGBA32I: return 16;
        default: break;
    }
    // Any other sized format: the bits GL reports for its components.
    GLint bits = 0;
    for (GLenum component : {GL_INTERNALFORMAT_RED_SIZE, GL_INTERNALFORMAT_GREEN_SIZE, GL_INTERNALFORMAT_BLUE_SIZE,
                             GL_INTERNALFORMAT_ALPHA_SIZE, GL_INTERNALFORMAT_DEPTH_SIZE, GL_INTERNALFORMAT_STENCIL_SIZE}) {
        GLint b = 0;
        glGetInternalformativ(GL_TEXTURE_2D, format, component, 1, &b);
        bits += b;
    }
    return static_cast<uint64_t>((bits + 7) / 8);
}

uint64_t textureStorageBytes(const TextureDesc& d) {
    const uint64_t texel = texelBytes(d.format);
    const bool volume = d.target == GL_TEXTURE_3D;
    const uint64_t faces = d.target == GL_TEXTURE_CUBE_MAP ? 6 : 1;
    const uint64_t samples = d.samples > 0 ? static_cast<uint64_t>(d.samples) : 1;
    uint64_t total = 0;
    for (int level = 0; level < d.levels; ++level) {
        const uint64_t w = static_cast<uint64_t>(std::max(1, d.width >> level));
        const uint64_t h = static_cast<uint64_t>(std::max(1, d.height >> level));
        const uint64_t z = static_cast<uint64_t>(volume ? std::max(1, d.depth >> level) : d.depth);
        total += w * h * z * faces * samples * texel;
    }
    return total;
}

Buffer Buffer::create(std::string_view name, size_t bytes, const void* data, GLbitfield flags) {
    BOUNCE_CHECK(bytes > 0, "buffer '{}' of zero size", name);
    throwIfPastFreeMemory("buffer", name, bytes);
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer b;
    b.m_handle = Handle<BufferTraits>(id);
    b.m_size = bytes;
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
    throwIfOutOfMemory("buffer", name, bytes);
    ledger::storage(ObjectKind::Buffer, id, bytes);
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

Texture Texture::createBufferView(std::string_view name, const Buffer& buffer, GLenum format) {
    BOUNCE_CHECK(static_cast<bool>(buffer), "buffer texture '{}' views a buffer", name);
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    Texture t;
    t.m_handle = Handle<TextureTraits>(id);
    t.m_desc.target = GL_TEXTURE_BUFFER;
    t.m_desc.format = format;
    t.m_desc.width = static_cast<int>(buffer.size() / texelBytes(format));
    glTextureBuffer(id, format, buffer.id());
    label(GL_TEXTURE, id, name);
    return t;
}

Texture Texture::createView(std::string_view name, const Texture& source, GLenum format) {
    BOUNCE_CHECK(static_cast<bool>(source), "texture view '{}' views a texture", name);
    GLuint id = 0;
    glGenTextures(1, &id);  // glTextureView wants a name that was never bound (not glCreateTextures')
    glTextureView(id, source.m_desc.target, source.id(), format, 0, static_cast<GLuint>(source.m_desc.levels), 0,
                  source.m_desc.target == GL_TEXTURE_2D ? 1u : static_cast<GLuint>(source.m_desc.depth));
    Texture t;
    t.m_handle = Handle<TextureTraits>(id);
    t.m_desc = source.m_desc;
    t.m_desc.format = format;
    label(GL_TEXTURE, id, name);
    return t;
}

Texture Texture::create(std::string_view name, const TextureDesc& desc) {
    BOUNCE_CHECK(desc.width > 0 && desc.height > 0 && desc.depth > 0 && desc.levels > 0, "texture '{}' has size {}x{}x{}",
                 name, desc.width, desc.height, desc.depth);
    const uint64_t bytes = textureStorageBytes(desc);
    throwIfPastFreeMemory("texture", name, bytes);
    GLuint id = 0;
    glCreateTextures(desc.target, 1, &id);
    Texture t;
    t.m_handle = Handle<TextureTraits>(id);
    t.m_desc = desc;
    const auto allocated = [&] {
        throwIfOutOfMemory("texture", name, bytes);
        ledger::storage(ObjectKind::Texture, id, bytes);
        label(GL_TEXTURE, id, name);
    };
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
            allocated();
            return t;
        case GL_TEXTURE_2D_MULTISAMPLE_ARRAY:
            // Multisampled textures have no sampler state: setting filters on them is an error.
            glTextureStorage3DMultisample(id, desc.samples, desc.format, desc.width, desc.height, desc.depth, GL_TRUE);
            allocated();
            return t;
        default: BOUNCE_CHECK(false, "texture '{}': unsupported target 0x{:x}", name, desc.target);
    }
    allocated();
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(desc.minFilter));
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(desc.magFilter));
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(desc.wrap));
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(desc.wrap));
    glTextureParameteri(id, GL_TEXTURE_WRAP_R, static_cast<GLint>(desc.wrap));
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

Texture Texture::create2DArray(std::string_view name, int width, int height, int layers, GLenum format, int levels,
                               GLenum filter) {
    TextureDesc d;
    d.target = GL_TEXTURE_2D_ARRAY;
    d.format = format;
    d.width = width;
    d.height = height;
    d.depth = layers;
    d.levels = levels;
    d.minFilter = levels == 1 ? filter : filter == GL_LINEAR ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    d.magFilter = filter;
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
