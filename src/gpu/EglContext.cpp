// Headless OpenGL 4.5 core through EGL. On a machine with a GPU (NVIDIA) the EGL device platform
// gives a context without any window system; without one, Mesa's surfaceless platform gives
// llvmpipe. Rendering always goes to framebuffer objects, so no EGL surface is created.
#include "gpu/Context.h"

#include <epoxy/egl.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace bounce::gl {

namespace {

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

class EglContext final : public Context {
public:
    EglContext(EGLDisplay display, EGLContext context) : m_display(display), m_context(context) {}
    ~EglContext() override {
        releaseObjects();
        eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(m_display, m_context);
        eglTerminate(m_display);
    }
    void makeCurrent() override { eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_context); }
    bool headless() const override { return true; }
    using Context::initialise;

private:
    EGLDisplay m_display;
    EGLContext m_context;
};

// A hardware EGL device (not Mesa's software device), or EGL_NO_DEVICE_EXT.
EGLDeviceEXT findHardwareDevice() {
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExts, "EGL_EXT_device_enumeration") && !hasExtension(clientExts, "EGL_EXT_device_base"))
        return EGL_NO_DEVICE_EXT;
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devices, &count)) return EGL_NO_DEVICE_EXT;
    for (EGLint i = 0; i < count; ++i) {
        const char* exts = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        if (!hasExtension(exts, "EGL_MESA_device_software")) return devices[i];
    }
    return EGL_NO_DEVICE_EXT;
}

std::string eglErrorName(EGLint e) {
    switch (e) {
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        default: return fmt::format("0x{:x}", e);
    }
}

}  // namespace

Expected<std::unique_ptr<Context>> Context::createHeadless(const ContextConfig& config) {
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExts) return makeError("EGL: no client extensions (is libEGL installed?)");
    const char* forced = std::getenv("BOUNCE_EGL_PLATFORM");
    const std::string force = forced ? forced : "";
    if (!force.empty() && force != "device" && force != "surfaceless")
        return makeError("BOUNCE_EGL_PLATFORM='{}' is not 'device' or 'surfaceless'", force);

    EGLDisplay display = EGL_NO_DISPLAY;
    std::string platform;
    if (force != "surfaceless") {
        EGLDeviceEXT device = findHardwareDevice();
        if (device != EGL_NO_DEVICE_EXT) {
            display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
            platform = "egl-device";
        } else if (force == "device") {
            return makeError("EGL: BOUNCE_EGL_PLATFORM=device but no hardware EGL device was found");
        }
    }
    if (display == EGL_NO_DISPLAY) {
        if (!hasExtension(clientExts, "EGL_MESA_platform_surfaceless"))
            return makeError("EGL: no GPU device and no EGL_MESA_platform_surfaceless (install libegl-mesa0)");
        display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        platform = "egl-surfaceless";
    }
    if (display == EGL_NO_DISPLAY) return makeError("EGL: cannot get a display ({})", platform);
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
        return makeError("EGL: eglInitialize failed on {}: {}", platform, eglErrorName(eglGetError()));
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(display);
        return makeError("EGL: desktop OpenGL API not available on {}", platform);
    }
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig eglConfig = nullptr;
    EGLint numConfigs = 0;
    const char* displayExts = eglQueryString(display, EGL_EXTENSIONS);
    const bool noConfig = hasExtension(displayExts, "EGL_KHR_no_config_context");
    if (!noConfig && (!eglChooseConfig(display, configAttribs, &eglConfig, 1, &numConfigs) || numConfigs == 0)) {
        eglTerminate(display);
        return makeError("EGL: no OpenGL config on {}", platform);
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG, config.debugOutput ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    EGLContext context =
        eglCreateContext(display, noConfig ? EGL_NO_CONFIG_KHR : eglConfig, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) {
        const EGLint err = eglGetError();
        eglTerminate(display);
        return makeError("EGL: cannot create an OpenGL 4.5 core context on {}: {}", platform, eglErrorName(err));
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(display, context);
        eglTerminate(display);
        return makeError("EGL: eglMakeCurrent without surface failed on {}", platform);
    }
    auto ctx = std::make_unique<EglContext>(display, context);
    if (epoxy_gl_version() < 45) return makeError("EGL: context reports OpenGL {}, need 4.5", epoxy_gl_version());
    ctx->initialise(config, platform);
    spdlog::debug("EGL {}.{} context on {}: {}", major, minor, platform, ctx->info().renderer);
    return std::unique_ptr<Context>(std::move(ctx));
}

}  // namespace bounce::gl
