#include "gpu/BarrierTracker.h"

#include "core/Check.h"
#include "gpu/ProgramChecks.h"
#include "gpu/Readbacks.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <cstdlib>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace bounce::gl {

namespace {

// What a program reads and may write, from GL's program interface queries (once per program).
struct ProgramResources {
    std::vector<GLuint> uniformBlocks;  // binding points
    std::vector<GLuint> storageBlocks;  // binding points: written, conservatively
    std::vector<GLuint> samplerUnits;
    std::vector<GLuint> imageUnits;     // written when the unit's access is not GL_READ_ONLY
};

// A shader write whose barrier bits are not all issued yet.
struct Pending {
    GLbitfield bits = 0;
    GLuint writer = 0;  // the program that wrote last
};

bool g_installed = false;
bool g_on = false;
std::unordered_map<GLuint, ProgramResources> g_programs;
std::unordered_map<GLuint, Pending> g_buffers, g_textures;
std::unordered_map<GLuint, GLuint> g_unitTexture;     // texture unit -> texture (glBindTextureUnit)
std::unordered_map<GLuint, GLuint> g_textureBuffer;   // buffer texture -> its buffer (glTextureBuffer)
std::unordered_map<GLuint, std::set<GLuint>> g_vaoBuffers;  // vertex array -> vertex buffers
std::unordered_map<GLuint, GLuint> g_vaoElements;     // vertex array -> element buffer
std::unordered_map<GLuint, std::set<std::string>> g_readonlyBlocks;  // program -> readonly storage block names
std::vector<std::string> g_violations;
std::set<std::tuple<GLuint, GLuint, std::string>> g_reported;  // (reader program, object, kind)

GLint getIndexed(GLenum pname, GLuint index) {
    GLint v = 0;
    glGetIntegeri_v(pname, index, &v);
    return v;
}

std::string label(GLenum kind, GLuint id) {
    char text[128] = {};
    GLsizei length = 0;
    if (id != 0) glGetObjectLabel(kind, id, sizeof(text), &length, text);
    const std::string name = length > 0 ? std::string(text, static_cast<size_t>(length)) : std::string("unlabelled");
    return fmt::format("'{}' ({})", name, id);
}

const ProgramResources& resources(GLuint program) {
    auto it = g_programs.find(program);
    if (it != g_programs.end()) return it->second;
    ProgramResources r;
    auto blocks = [&](GLenum iface, std::vector<GLuint>& out) {
        GLint n = 0;
        glGetProgramInterfaceiv(program, iface, GL_ACTIVE_RESOURCES, &n);
        for (GLint i = 0; i < n; ++i) {
            const GLenum prop = GL_BUFFER_BINDING;
            GLint binding = 0;
            glGetProgramResourceiv(program, iface, static_cast<GLuint>(i), 1, &prop, 1, nullptr, &binding);
            out.push_back(static_cast<GLuint>(binding));
        }
    };
    blocks(GL_UNIFORM_BLOCK, r.uniformBlocks);
    blocks(GL_SHADER_STORAGE_BLOCK, r.storageBlocks);
    // Drop the blocks the sources declare readonly (GL reports no qualifiers).
    if (auto ro = g_readonlyBlocks.find(program); ro != g_readonlyBlocks.end()) {
        std::vector<GLuint> writable;
        for (size_t i = 0; i < r.storageBlocks.size(); ++i) {
            char name[256] = {};
            glGetProgramResourceName(program, GL_SHADER_STORAGE_BLOCK, static_cast<GLuint>(i), sizeof(name), nullptr, name);
            std::string base(name);
            base = base.substr(0, base.find('['));
            if (!ro->second.count(base)) writable.push_back(r.storageBlocks[i]);
        }
        r.storageBlocks = std::move(writable);
    }
    GLint n = 0;
    glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &n);
    for (GLint i = 0; i < n; ++i) {
        const GLenum props[3] = {GL_TYPE, GL_LOCATION, GL_ARRAY_SIZE};
        GLint v[3] = {};
        glGetProgramResourceiv(program, GL_UNIFORM, static_cast<GLuint>(i), 3, props, 3, nullptr, v);
        const GLenum type = static_cast<GLenum>(v[0]);
        const bool image = isImageType(type), sampler = isSamplerType(type);
        if ((!image && !sampler) || v[1] < 0) continue;
        for (GLint k = 0; k < std::max(1, v[2]); ++k) {
            GLint unit = 0;
            glGetUniformiv(program, v[1] + k, &unit);
            (image ? r.imageUnits : r.samplerUnits).push_back(static_cast<GLuint>(unit));
        }
    }
    return g_programs.emplace(program, std::move(r)).first->second;
}

const char* bitName(GLbitfield bit) {
    switch (bit) {
        case GL_UNIFORM_BARRIER_BIT: return "GL_UNIFORM_BARRIER_BIT";
        case GL_TEXTURE_FETCH_BARRIER_BIT: return "GL_TEXTURE_FETCH_BARRIER_BIT";
        case GL_COMMAND_BARRIER_BIT: return "GL_COMMAND_BARRIER_BIT";
        case GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT: return "GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT";
        case GL_ELEMENT_ARRAY_BARRIER_BIT: return "GL_ELEMENT_ARRAY_BARRIER_BIT";
        case GL_BUFFER_UPDATE_BARRIER_BIT: return "GL_BUFFER_UPDATE_BARRIER_BIT";
        case GL_TEXTURE_UPDATE_BARRIER_BIT: return "GL_TEXTURE_UPDATE_BARRIER_BIT";
        default: return "a barrier bit";
    }
}

// A read of `object` (a buffer when isBuffer, else a texture) that needs `bit`: a violation if a shader
// wrote the object and no glMemoryBarrier with `bit` came since.
void read(bool isBuffer, GLuint object, GLbitfield bit, GLuint reader, const std::string& how) {
    if (object == 0) return;
    auto& table = isBuffer ? g_buffers : g_textures;
    auto it = table.find(object);
    if (it == table.end() || !(it->second.bits & bit)) return;
    if (!g_reported.emplace(reader, object, how).second) return;
    g_violations.push_back(fmt::format("{} {} read as {} after program {} wrote it, without glMemoryBarrier({}) since{}",
                                       isBuffer ? "buffer" : "texture", label(isBuffer ? GL_BUFFER : GL_TEXTURE, object), how,
                                       label(GL_PROGRAM, it->second.writer), bitName(bit),
                                       reader ? fmt::format(" (reader: program {})", label(GL_PROGRAM, reader)) : std::string()));
}

void written(bool isBuffer, GLuint object, GLuint writer) {
    if (object == 0) return;
    (isBuffer ? g_buffers : g_textures)[object] = Pending{GL_ALL_BARRIER_BITS, writer};
}

enum class Call { Draw, DrawIndirect, DrawElements, DrawElementsIndirect, Dispatch, DispatchIndirect };

// Before a draw or dispatch: its reads are checked, then its writes recorded.
void beforeCall(Call call) {
    if (!g_on) return;
    GLint current = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    const GLuint program = static_cast<GLuint>(current);
    if (program == 0) return;
    const ProgramResources& r = resources(program);
    for (GLuint b : r.uniformBlocks)
        read(true, static_cast<GLuint>(getIndexed(GL_UNIFORM_BUFFER_BINDING, b)), GL_UNIFORM_BARRIER_BIT, program,
             fmt::format("a uniform block (binding {})", b));
    for (GLuint u : r.samplerUnits) {
        auto t = g_unitTexture.find(u);
        if (t == g_unitTexture.end()) continue;
        const std::string how = fmt::format("a sampler (unit {})", u);
        read(false, t->second, GL_TEXTURE_FETCH_BARRIER_BIT, program, how);
        auto tb = g_textureBuffer.find(t->second);
        if (tb != g_textureBuffer.end()) read(true, tb->second, GL_TEXTURE_FETCH_BARRIER_BIT, program, how + " of a buffer texture");
    }
    if (call == Call::DrawIndirect || call == Call::DrawElementsIndirect) {
        GLint b = 0;
        glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &b);
        read(true, static_cast<GLuint>(b), GL_COMMAND_BARRIER_BIT, program, "indirect draw arguments");
    }
    if (call == Call::DispatchIndirect) {
        GLint b = 0;
        glGetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &b);
        read(true, static_cast<GLuint>(b), GL_COMMAND_BARRIER_BIT, program, "indirect dispatch arguments");
    }
    if (call != Call::Dispatch && call != Call::DispatchIndirect) {
        GLint vao = 0;
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        auto vb = g_vaoBuffers.find(static_cast<GLuint>(vao));
        if (vb != g_vaoBuffers.end())
            for (GLuint b : vb->second) read(true, b, GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT, program, "vertex attributes");
        auto eb = g_vaoElements.find(static_cast<GLuint>(vao));
        if ((call == Call::DrawElements || call == Call::DrawElementsIndirect) && eb != g_vaoElements.end())
            read(true, eb->second, GL_ELEMENT_ARRAY_BARRIER_BIT, program, "indices");
    }
    for (GLuint b : r.storageBlocks) written(true, static_cast<GLuint>(getIndexed(GL_SHADER_STORAGE_BUFFER_BINDING, b)), program);
    for (GLuint u : r.imageUnits) {
        if (getIndexed(GL_IMAGE_BINDING_ACCESS, u) == GL_READ_ONLY) continue;
        const GLuint texture = static_cast<GLuint>(getIndexed(GL_IMAGE_BINDING_NAME, u));
        written(false, texture, program);
        auto tb = g_textureBuffer.find(texture);
        if (tb != g_textureBuffer.end()) written(true, tb->second, program);
    }
}

void barrier(GLbitfield bits) {
    for (auto* table : {&g_buffers, &g_textures})
        for (auto it = table->begin(); it != table->end();) {
            it->second.bits &= ~bits;
            it = it->second.bits == 0 ? table->erase(it) : std::next(it);
        }
}

template <typename F>
F resolve(const char* name) {
    auto f = reinterpret_cast<F>(eglGetProcAddress(name));
    BOUNCE_CHECK(f != nullptr, "barrier tracker: no GL entry point {}", name);
    return f;
}

// Hooks: the real entry point, resolved once, and a wrapper.
PFNGLDRAWARRAYSPROC real_drawArrays;
PFNGLDRAWARRAYSINSTANCEDPROC real_drawArraysInstanced;
PFNGLDRAWARRAYSINDIRECTPROC real_drawArraysIndirect;
PFNGLMULTIDRAWARRAYSINDIRECTPROC real_multiDrawArraysIndirect;
PFNGLDRAWELEMENTSPROC real_drawElements;
PFNGLDRAWELEMENTSINSTANCEDPROC real_drawElementsInstanced;
PFNGLDRAWELEMENTSINDIRECTPROC real_drawElementsIndirect;
PFNGLMULTIDRAWELEMENTSINDIRECTPROC real_multiDrawElementsIndirect;
PFNGLDRAWTRANSFORMFEEDBACKPROC real_drawTransformFeedback;
PFNGLDRAWTRANSFORMFEEDBACKINSTANCEDPROC real_drawTransformFeedbackInstanced;
PFNGLDISPATCHCOMPUTEPROC real_dispatchCompute;
PFNGLDISPATCHCOMPUTEINDIRECTPROC real_dispatchComputeIndirect;
PFNGLMEMORYBARRIERPROC real_memoryBarrier;
PFNGLMEMORYBARRIERBYREGIONPROC real_memoryBarrierByRegion;
PFNGLBINDTEXTUREUNITPROC real_bindTextureUnit;
PFNGLTEXTUREBUFFERPROC real_textureBuffer;
PFNGLTEXTUREBUFFERRANGEPROC real_textureBufferRange;
PFNGLVERTEXARRAYVERTEXBUFFERPROC real_vertexArrayVertexBuffer;
PFNGLVERTEXARRAYELEMENTBUFFERPROC real_vertexArrayElementBuffer;
PFNGLDELETEBUFFERSPROC real_deleteBuffers;
PFNGLDELETETEXTURESPROC real_deleteTextures;
PFNGLDELETEPROGRAMPROC real_deleteProgram;
PFNGLDELETEVERTEXARRAYSPROC real_deleteVertexArrays;

void EPOXY_CALLSPEC hook_drawArrays(GLenum m, GLint f, GLsizei c) {
    beforeCall(Call::Draw);
    real_drawArrays(m, f, c);
}
void EPOXY_CALLSPEC hook_drawArraysInstanced(GLenum m, GLint f, GLsizei c, GLsizei n) {
    beforeCall(Call::Draw);
    real_drawArraysInstanced(m, f, c, n);
}
void EPOXY_CALLSPEC hook_drawArraysIndirect(GLenum m, const void* i) {
    beforeCall(Call::DrawIndirect);
    real_drawArraysIndirect(m, i);
}
void EPOXY_CALLSPEC hook_multiDrawArraysIndirect(GLenum m, const void* i, GLsizei n, GLsizei s) {
    beforeCall(Call::DrawIndirect);
    real_multiDrawArraysIndirect(m, i, n, s);
}
void EPOXY_CALLSPEC hook_drawElements(GLenum m, GLsizei c, GLenum t, const void* i) {
    beforeCall(Call::DrawElements);
    real_drawElements(m, c, t, i);
}
void EPOXY_CALLSPEC hook_drawElementsInstanced(GLenum m, GLsizei c, GLenum t, const void* i, GLsizei n) {
    beforeCall(Call::DrawElements);
    real_drawElementsInstanced(m, c, t, i, n);
}
void EPOXY_CALLSPEC hook_drawElementsIndirect(GLenum m, GLenum t, const void* i) {
    beforeCall(Call::DrawElementsIndirect);
    real_drawElementsIndirect(m, t, i);
}
void EPOXY_CALLSPEC hook_multiDrawElementsIndirect(GLenum m, GLenum t, const void* i, GLsizei n, GLsizei s) {
    beforeCall(Call::DrawElementsIndirect);
    real_multiDrawElementsIndirect(m, t, i, n, s);
}
void EPOXY_CALLSPEC hook_drawTransformFeedback(GLenum m, GLuint id) {
    beforeCall(Call::Draw);
    real_drawTransformFeedback(m, id);
}
void EPOXY_CALLSPEC hook_drawTransformFeedbackInstanced(GLenum m, GLuint id, GLsizei n) {
    beforeCall(Call::Draw);
    real_drawTransformFeedbackInstanced(m, id, n);
}
void EPOXY_CALLSPEC hook_dispatchCompute(GLuint x, GLuint y, GLuint z) {
    beforeCall(Call::Dispatch);
    real_dispatchCompute(x, y, z);
}
void EPOXY_CALLSPEC hook_dispatchComputeIndirect(GLintptr o) {
    beforeCall(Call::DispatchIndirect);
    real_dispatchComputeIndirect(o);
}
void EPOXY_CALLSPEC hook_memoryBarrier(GLbitfield bits) {
    if (g_on) barrier(bits);
    real_memoryBarrier(bits);
}
void EPOXY_CALLSPEC hook_memoryBarrierByRegion(GLbitfield bits) {
    if (g_on) barrier(bits);
    real_memoryBarrierByRegion(bits);
}
void EPOXY_CALLSPEC hook_bindTextureUnit(GLuint unit, GLuint texture) {
    g_unitTexture[unit] = texture;
    real_bindTextureUnit(unit, texture);
}
void EPOXY_CALLSPEC hook_textureBuffer(GLuint texture, GLenum format, GLuint buffer) {
    g_textureBuffer[texture] = buffer;
    real_textureBuffer(texture, format, buffer);
}
void EPOXY_CALLSPEC hook_textureBufferRange(GLuint texture, GLenum format, GLuint buffer, GLintptr o, GLsizeiptr s) {
    g_textureBuffer[texture] = buffer;
    real_textureBufferRange(texture, format, buffer, o, s);
}
void EPOXY_CALLSPEC hook_vertexArrayVertexBuffer(GLuint vao, GLuint index, GLuint buffer, GLintptr o, GLsizei s) {
    if (buffer) g_vaoBuffers[vao].insert(buffer);
    real_vertexArrayVertexBuffer(vao, index, buffer, o, s);
}
void EPOXY_CALLSPEC hook_vertexArrayElementBuffer(GLuint vao, GLuint buffer) {
    g_vaoElements[vao] = buffer;
    real_vertexArrayElementBuffer(vao, buffer);
}
// Deleted names are reused by GL: forget what was known of them.
void EPOXY_CALLSPEC hook_deleteBuffers(GLsizei n, const GLuint* ids) {
    for (GLsizei i = 0; i < n; ++i) {
        g_buffers.erase(ids[i]);
        for (auto& [vao, buffers] : g_vaoBuffers) buffers.erase(ids[i]);
    }
    real_deleteBuffers(n, ids);
}
void EPOXY_CALLSPEC hook_deleteTextures(GLsizei n, const GLuint* ids) {
    for (GLsizei i = 0; i < n; ++i) {
        g_textures.erase(ids[i]);
        g_textureBuffer.erase(ids[i]);
        for (auto& [unit, texture] : g_unitTexture)
            if (texture == ids[i]) texture = 0;
    }
    real_deleteTextures(n, ids);
}
void EPOXY_CALLSPEC hook_deleteProgram(GLuint id) {
    g_programs.erase(id);
    g_readonlyBlocks.erase(id);
    real_deleteProgram(id);
}
void EPOXY_CALLSPEC hook_deleteVertexArrays(GLsizei n, const GLuint* ids) {
    for (GLsizei i = 0; i < n; ++i) {
        g_vaoBuffers.erase(ids[i]);
        g_vaoElements.erase(ids[i]);
    }
    real_deleteVertexArrays(n, ids);
}

}  // namespace

void installBarrierTracker() {
    if (g_installed) return;
    installReadbackHooks();  // they report CPU reads to detail::barrierBufferRead/TextureRead
#define BOUNCE_HOOK(PFN, real, name, hook) \
    real = resolve<PFN>(#name);            \
    epoxy_##name = hook;
    BOUNCE_HOOK(PFNGLDRAWARRAYSPROC, real_drawArrays, glDrawArrays, hook_drawArrays)
    BOUNCE_HOOK(PFNGLDRAWARRAYSINSTANCEDPROC, real_drawArraysInstanced, glDrawArraysInstanced, hook_drawArraysInstanced)
    BOUNCE_HOOK(PFNGLDRAWARRAYSINDIRECTPROC, real_drawArraysIndirect, glDrawArraysIndirect, hook_drawArraysIndirect)
    BOUNCE_HOOK(PFNGLMULTIDRAWARRAYSINDIRECTPROC, real_multiDrawArraysIndirect, glMultiDrawArraysIndirect, hook_multiDrawArraysIndirect)
    BOUNCE_HOOK(PFNGLDRAWELEMENTSPROC, real_drawElements, glDrawElements, hook_drawElements)
    BOUNCE_HOOK(PFNGLDRAWELEMENTSINSTANCEDPROC, real_drawElementsInstanced, glDrawElementsInstanced, hook_drawElementsInstanced)
    BOUNCE_HOOK(PFNGLDRAWELEMENTSINDIRECTPROC, real_drawElementsIndirect, glDrawElementsIndirect, hook_drawElementsIndirect)
    BOUNCE_HOOK(PFNGLMULTIDRAWELEMENTSINDIRECTPROC, real_multiDrawElementsIndirect, glMultiDrawElementsIndirect,
                hook_multiDrawElementsIndirect)
    BOUNCE_HOOK(PFNGLDRAWTRANSFORMFEEDBACKPROC, real_drawTransformFeedback, glDrawTransformFeedback, hook_drawTransformFeedback)
    BOUNCE_HOOK(PFNGLDRAWTRANSFORMFEEDBACKINSTANCEDPROC, real_drawTransformFeedbackInstanced, glDrawTransformFeedbackInstanced,
                hook_drawTransformFeedbackInstanced)
    BOUNCE_HOOK(PFNGLDISPATCHCOMPUTEPROC, real_dispatchCompute, glDispatchCompute, hook_dispatchCompute)
    BOUNCE_HOOK(PFNGLDISPATCHCOMPUTEINDIRECTPROC, real_dispatchComputeIndirect, glDispatchComputeIndirect, hook_dispatchComputeIndirect)
    BOUNCE_HOOK(PFNGLMEMORYBARRIERPROC, real_memoryBarrier, glMemoryBarrier, hook_memoryBarrier)
    BOUNCE_HOOK(PFNGLMEMORYBARRIERBYREGIONPROC, real_memoryBarrierByRegion, glMemoryBarrierByRegion, hook_memoryBarrierByRegion)
    BOUNCE_HOOK(PFNGLBINDTEXTUREUNITPROC, real_bindTextureUnit, glBindTextureUnit, hook_bindTextureUnit)
    BOUNCE_HOOK(PFNGLTEXTUREBUFFERPROC, real_textureBuffer, glTextureBuffer, hook_textureBuffer)
    BOUNCE_HOOK(PFNGLTEXTUREBUFFERRANGEPROC, real_textureBufferRange, glTextureBufferRange, hook_textureBufferRange)
    BOUNCE_HOOK(PFNGLVERTEXARRAYVERTEXBUFFERPROC, real_vertexArrayVertexBuffer, glVertexArrayVertexBuffer, hook_vertexArrayVertexBuffer)
    BOUNCE_HOOK(PFNGLVERTEXARRAYELEMENTBUFFERPROC, real_vertexArrayElementBuffer, glVertexArrayElementBuffer, hook_vertexArrayElementBuffer)
    BOUNCE_HOOK(PFNGLDELETEBUFFERSPROC, real_deleteBuffers, glDeleteBuffers, hook_deleteBuffers)
    BOUNCE_HOOK(PFNGLDELETETEXTURESPROC, real_deleteTextures, glDeleteTextures, hook_deleteTextures)
    BOUNCE_HOOK(PFNGLDELETEPROGRAMPROC, real_deleteProgram, glDeleteProgram, hook_deleteProgram)
    BOUNCE_HOOK(PFNGLDELETEVERTEXARRAYSPROC, real_deleteVertexArrays, glDeleteVertexArrays, hook_deleteVertexArrays)
#undef BOUNCE_HOOK
    g_installed = true;
}

void setBarrierTracking(bool on) {
    BOUNCE_CHECK(!on || g_installed, "barrier tracking needs installBarrierTracker()");
    g_on = on;
}
bool barrierTracking() { return g_on; }

bool barrierCheckRequested() {
    const char* v = std::getenv("BOUNCE_BARRIER_CHECK");
    return v && std::string(v) == "1";
}

const std::vector<std::string>& barrierViolations() { return g_violations; }
void resetBarrierViolations() {
    g_violations.clear();
    g_reported.clear();
}
void resetBarrierState() {
    g_buffers.clear();
    g_textures.clear();
}

namespace detail {
void barrierBufferRead(unsigned buffer, const char* how) {
    if (g_on) read(true, buffer, GL_BUFFER_UPDATE_BARRIER_BIT, 0, how);
}
void barrierTextureRead(unsigned texture, const char* how) {
    if (g_on) read(false, texture, GL_TEXTURE_UPDATE_BARRIER_BIT, 0, how);
}
void barrierNoteProgramSources(unsigned program, const std::vector<std::string>& texts) {
    // `... readonly ... buffer NAME {`: the qualifiers between the previous declaration's end and `buffer`.
    static const std::regex kBlock(R"(\bbuffer\s+(\w+)\s*\{)");
    static const std::regex kReadonly(R"(\breadonly\b)");
    std::set<std::string> readonly;
    for (const std::string& text : texts)
        for (auto it = std::sregex_iterator(text.begin(), text.end(), kBlock); it != std::sregex_iterator(); ++it) {
            const size_t at = static_cast<size_t>(it->position(0));
            const size_t from = text.find_last_of(";{}", at);
            const std::string qualifiers = text.substr(from == std::string::npos ? 0 : from + 1, at - (from == std::string::npos ? 0 : from + 1));
            if (std::regex_search(qualifiers, kReadonly)) readonly.insert((*it)[1].str());
        }
    g_readonlyBlocks[program] = std::move(readonly);
    g_programs.erase(program);
}
}  // namespace detail

}  // namespace bounce::gl
