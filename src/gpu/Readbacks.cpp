#include "gpu/Readbacks.h"

#include "core/Check.h"
#include "gpu/BarrierTracker.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

namespace bounce::gl {

namespace {

int g_depth = 0;
bool g_installed = false;
std::vector<std::string> g_log;

void note(const char* name) {
    if (g_depth > 0) g_log.emplace_back(name);
}

// A query read does not wait when it asks only for availability or for whatever is there, or when the
// result goes into a bound query buffer (GL 4.4 ARB_query_buffer_object) rather than to the CPU.
bool queryReadWaits(GLenum pname) {
    if (pname == GL_QUERY_RESULT_AVAILABLE || pname == GL_QUERY_RESULT_NO_WAIT) return false;
    GLint queryBuffer = 0;
    glGetIntegerv(GL_QUERY_BUFFER_BINDING, &queryBuffer);
    return queryBuffer == 0;
}

// The buffer bound to `target` (the barrier tracker's view of a target-based read).
GLuint boundBuffer(GLenum target) {
    GLenum binding = 0;
    switch (target) {
        case GL_ARRAY_BUFFER: binding = GL_ARRAY_BUFFER_BINDING; break;
        case GL_SHADER_STORAGE_BUFFER: binding = GL_SHADER_STORAGE_BUFFER_BINDING; break;
        case GL_UNIFORM_BUFFER: binding = GL_UNIFORM_BUFFER_BINDING; break;
        case GL_COPY_READ_BUFFER: binding = GL_COPY_READ_BUFFER_BINDING; break;
        case GL_COPY_WRITE_BUFFER: binding = GL_COPY_WRITE_BUFFER_BINDING; break;
        case GL_PIXEL_PACK_BUFFER: binding = GL_PIXEL_PACK_BUFFER_BINDING; break;
        case GL_DRAW_INDIRECT_BUFFER: binding = GL_DRAW_INDIRECT_BUFFER_BINDING; break;
        case GL_DISPATCH_INDIRECT_BUFFER: binding = GL_DISPATCH_INDIRECT_BUFFER_BINDING; break;
        default: return 0;
    }
    GLint id = 0;
    glGetIntegerv(binding, &id);
    return static_cast<GLuint>(id);
}

template <typename F>
F resolve(const char* name) {
    auto f = reinterpret_cast<F>(eglGetProcAddress(name));
    BOUNCE_CHECK(f != nullptr, "readback hooks: no GL entry point {}", name);
    return f;
}

// One hook per entry point: the real function, resolved once, and a wrapper that logs then forwards.
#define BOUNCE_QUERY_HOOK(PFN, NAME, T)                                    \
    PFN real_##NAME = nullptr;                                              \
    void EPOXY_CALLSPEC hook_##NAME(GLuint id, GLenum pname, T* params) {  \
        if (queryReadWaits(pname)) note(#NAME);                             \
        real_##NAME(id, pname, params);                                     \
    }
BOUNCE_QUERY_HOOK(PFNGLGETQUERYOBJECTIVPROC, glGetQueryObjectiv, GLint)
BOUNCE_QUERY_HOOK(PFNGLGETQUERYOBJECTUIVPROC, glGetQueryObjectuiv, GLuint)
BOUNCE_QUERY_HOOK(PFNGLGETQUERYOBJECTI64VPROC, glGetQueryObjecti64v, GLint64)
BOUNCE_QUERY_HOOK(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v, GLuint64)
#undef BOUNCE_QUERY_HOOK

PFNGLGETNAMEDBUFFERSUBDATAPROC real_getNamedBufferSubData = nullptr;
void EPOXY_CALLSPEC hook_getNamedBufferSubData(GLuint b, GLintptr o, GLsizeiptr s, void* d) {
    note("glGetNamedBufferSubData");
    detail::barrierBufferRead(b, "a readback (glGetNamedBufferSubData)");
    real_getNamedBufferSubData(b, o, s, d);
}
PFNGLGETBUFFERSUBDATAPROC real_getBufferSubData = nullptr;
void EPOXY_CALLSPEC hook_getBufferSubData(GLenum t, GLintptr o, GLsizeiptr s, void* d) {
    note("glGetBufferSubData");
    if (barrierTracking()) detail::barrierBufferRead(boundBuffer(t), "a readback (glGetBufferSubData)");
    real_getBufferSubData(t, o, s, d);
}
// Mapping waits for the GPU's pending writes unless the caller asks for an unsynchronised map.
PFNGLMAPNAMEDBUFFERRANGEPROC real_mapNamedBufferRange = nullptr;
void* EPOXY_CALLSPEC hook_mapNamedBufferRange(GLuint b, GLintptr o, GLsizeiptr s, GLbitfield a) {
    if (!(a & GL_MAP_UNSYNCHRONIZED_BIT)) note("glMapNamedBufferRange");
    detail::barrierBufferRead(b, "a mapping (glMapNamedBufferRange)");
    return real_mapNamedBufferRange(b, o, s, a);
}
PFNGLMAPBUFFERRANGEPROC real_mapBufferRange = nullptr;
void* EPOXY_CALLSPEC hook_mapBufferRange(GLenum t, GLintptr o, GLsizeiptr s, GLbitfield a) {
    if (!(a & GL_MAP_UNSYNCHRONIZED_BIT)) note("glMapBufferRange");
    if (barrierTracking()) detail::barrierBufferRead(boundBuffer(t), "a mapping (glMapBufferRange)");
    return real_mapBufferRange(t, o, s, a);
}
PFNGLMAPNAMEDBUFFERPROC real_mapNamedBuffer = nullptr;
void* EPOXY_CALLSPEC hook_mapNamedBuffer(GLuint b, GLenum a) {
    note("glMapNamedBuffer");
    detail::barrierBufferRead(b, "a mapping (glMapNamedBuffer)");
    return real_mapNamedBuffer(b, a);
}
PFNGLMAPBUFFERPROC real_mapBuffer = nullptr;
void* EPOXY_CALLSPEC hook_mapBuffer(GLenum t, GLenum a) {
    note("glMapBuffer");
    if (barrierTracking()) detail::barrierBufferRead(boundBuffer(t), "a mapping (glMapBuffer)");
    return real_mapBuffer(t, a);
}
PFNGLGETTEXTUREIMAGEPROC real_getTextureImage = nullptr;
void EPOXY_CALLSPEC hook_getTextureImage(GLuint t, GLint l, GLenum f, GLenum ty, GLsizei s, void* p) {
    note("glGetTextureImage");
    detail::barrierTextureRead(t, "a readback (glGetTextureImage)");
    real_getTextureImage(t, l, f, ty, s, p);
}
PFNGLGETTEXTURESUBIMAGEPROC real_getTextureSubImage = nullptr;
void EPOXY_CALLSPEC hook_getTextureSubImage(GLuint t, GLint l, GLint x, GLint y, GLint z, GLsizei w, GLsizei h,
                                            GLsizei d, GLenum f, GLenum ty, GLsizei s, void* p) {
    note("glGetTextureSubImage");
    detail::barrierTextureRead(t, "a readback (glGetTextureSubImage)");
    real_getTextureSubImage(t, l, x, y, z, w, h, d, f, ty, s, p);
}
PFNGLGETTEXIMAGEPROC real_getTexImage = nullptr;
void EPOXY_CALLSPEC hook_getTexImage(GLenum t, GLint l, GLenum f, GLenum ty, void* p) {
    note("glGetTexImage");
    real_getTexImage(t, l, f, ty, p);
}
PFNGLREADPIXELSPROC real_readPixels = nullptr;
void EPOXY_CALLSPEC hook_readPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void* p) {
    note("glReadPixels");
    real_readPixels(x, y, w, h, f, t, p);
}
PFNGLREADNPIXELSPROC real_readnPixels = nullptr;
void EPOXY_CALLSPEC hook_readnPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, GLsizei s, void* p) {
    note("glReadnPixels");
    real_readnPixels(x, y, w, h, f, t, s, p);
}
PFNGLFINISHPROC real_finish = nullptr;
void EPOXY_CALLSPEC hook_finish() {
    note("glFinish");
    real_finish();
}
PFNGLCLIENTWAITSYNCPROC real_clientWaitSync = nullptr;
GLenum EPOXY_CALLSPEC hook_clientWaitSync(GLsync s, GLbitfield f, GLuint64 t) {
    if (t > 0) note("glClientWaitSync");  // a zero timeout only polls
    return real_clientWaitSync(s, f, t);
}

}  // namespace

FramePath::FramePath() { ++g_depth; }
FramePath::~FramePath() { --g_depth; }
bool inFramePath() { return g_depth > 0; }

void installReadbackHooks() {
    if (g_installed) return;
    real_glGetQueryObjectiv = resolve<PFNGLGETQUERYOBJECTIVPROC>("glGetQueryObjectiv");
    real_glGetQueryObjectuiv = resolve<PFNGLGETQUERYOBJECTUIVPROC>("glGetQueryObjectuiv");
    real_glGetQueryObjecti64v = resolve<PFNGLGETQUERYOBJECTI64VPROC>("glGetQueryObjecti64v");
    real_glGetQueryObjectui64v = resolve<PFNGLGETQUERYOBJECTUI64VPROC>("glGetQueryObjectui64v");
    real_getNamedBufferSubData = resolve<PFNGLGETNAMEDBUFFERSUBDATAPROC>("glGetNamedBufferSubData");
    real_getBufferSubData = resolve<PFNGLGETBUFFERSUBDATAPROC>("glGetBufferSubData");
    real_mapNamedBufferRange = resolve<PFNGLMAPNAMEDBUFFERRANGEPROC>("glMapNamedBufferRange");
    real_mapBufferRange = resolve<PFNGLMAPBUFFERRANGEPROC>("glMapBufferRange");
    real_mapNamedBuffer = resolve<PFNGLMAPNAMEDBUFFERPROC>("glMapNamedBuffer");
    real_mapBuffer = resolve<PFNGLMAPBUFFERPROC>("glMapBuffer");
    real_getTextureImage = resolve<PFNGLGETTEXTUREIMAGEPROC>("glGetTextureImage");
    real_getTextureSubImage = resolve<PFNGLGETTEXTURESUBIMAGEPROC>("glGetTextureSubImage");
    real_getTexImage = resolve<PFNGLGETTEXIMAGEPROC>("glGetTexImage");
    real_readPixels = resolve<PFNGLREADPIXELSPROC>("glReadPixels");
    real_readnPixels = resolve<PFNGLREADNPIXELSPROC>("glReadnPixels");
    real_finish = resolve<PFNGLFINISHPROC>("glFinish");
    real_clientWaitSync = resolve<PFNGLCLIENTWAITSYNCPROC>("glClientWaitSync");
    epoxy_glGetQueryObjectiv = hook_glGetQueryObjectiv;
    epoxy_glGetQueryObjectuiv = hook_glGetQueryObjectuiv;
    epoxy_glGetQueryObjecti64v = hook_glGetQueryObjecti64v;
    epoxy_glGetQueryObjectui64v = hook_glGetQueryObjectui64v;
    epoxy_glGetNamedBufferSubData = hook_getNamedBufferSubData;
    epoxy_glGetBufferSubData = hook_getBufferSubData;
    epoxy_glMapNamedBufferRange = hook_mapNamedBufferRange;
    epoxy_glMapBufferRange = hook_mapBufferRange;
    epoxy_glMapNamedBuffer = hook_mapNamedBuffer;
    epoxy_glMapBuffer = hook_mapBuffer;
    epoxy_glGetTextureImage = hook_getTextureImage;
    epoxy_glGetTextureSubImage = hook_getTextureSubImage;
    epoxy_glGetTexImage = hook_getTexImage;
    epoxy_glReadPixels = hook_readPixels;
    epoxy_glReadnPixels = hook_readnPixels;
    epoxy_glFinish = hook_finish;
    epoxy_glClientWaitSync = hook_clientWaitSync;
    g_installed = true;
}

bool readbackHooksInstalled() { return g_installed; }
const std::vector<std::string>& framePathReadbacks() { return g_log; }
void resetFramePathReadbacks() { g_log.clear(); }

}  // namespace bounce::gl
