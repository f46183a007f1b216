// Headless OpenGL 4.5 core through EGL. On a machine with a GPU the EGL device platform gives a
// context without any window system; without one, Mesa's surfaceless platform gives llvmpipe.
// Rendering always goes to framebuffer objects, so no EGL surface is created. Which device is used
// is decided by gpu/DeviceSelection.h from the enumeration below (issue 29 #2, #22).
#include "gpu/Context.h"
#include "gpu/DeviceSelection.h"

#include <epoxy/egl.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace bounce::gl {

namespace {

// EGL_EXT_device_drm_render_node and EGL_EXT_device_query_name (not in every epoxy's headers).
constexpr EGLint kEglDrmRenderNodeFileExt = 0x3377;
constexpr EGLint kEglRendererExt = 0x335F;
constexpr EGLint kEglVendor = 0x3053;  // EGL_VENDOR, which EGL_EXT_device_query_name also accepts
// At most this many devices are listed (eglQueryDevicesEXT's array); a machine has a handful.
constexpr EGLint kMaxEglDevices = 64;

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

std::vector<EGLDeviceEXT> queryDevices() {
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExts, "EGL_EXT_device_enumeration") && !hasExtension(clientExts, "EGL_EXT_device_base"))
        return {};
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(kMaxEglDevices));
    EGLint count = 0;
    if (!eglQueryDevicesEXT(kMaxEglDevices, devices.data(), &count)) return {};
    devices.resize(static_cast<size_t>(std::max(count, 0)));
    return devices;
}

EglDeviceDesc describe(EGLDeviceEXT device, int index) {
    EglDeviceDesc d;
    d.index = index;
    const char* exts = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
    d.software = hasExtension(exts, "EGL_MESA_device_software");
    auto str = [&](EGLint name) {
        const char* v = eglQueryDeviceStringEXT(device, name);
        eglGetError();  // an unsupported name is EGL_BAD_PARAMETER: not an error worth keeping
        return std::string(v ? v : "");
    };
    if (hasExtension(exts, "EGL_EXT_device_drm")) d.deviceFile = str(EGL_DRM_DEVICE_FILE_EXT);
    if (hasExtension(exts, "EGL_EXT_device_drm_render_node")) d.renderNode = str(kEglDrmRenderNodeFileExt);
    if (hasExtension(exts, "EGL_NV_device_cuda")) {
        EGLAttrib cuda = -1;
        if (eglQueryDeviceAttribEXT(device, EGL_CUDA_DEVICE_NV, &cuda)) d.cudaDevice = static_cast<int>(cuda);
    }
    const std::string node = !d.renderNode.empty() ? d.renderNode : d.deviceFile;
    if (!node.empty()) {
        std::error_code ec;
        const auto target = std::filesystem::read_symlink(
            std::filesystem::path("/sys/class/drm") / std::filesystem::path(node).filename() / "device/driver", ec);
        if (!ec) d.driver = target.filename().string();
    }
    if (hasExtension(exts, "EGL_EXT_device_query_name")) {
        const std::string vendor = str(kEglVendor), renderer = str(kEglRendererExt);
        d.name = vendor + (vendor.empty() || renderer.empty() ? "" : " ") + renderer;
    }
    if (d.name.empty()) {
        if (d.software) d.name = "Mesa software (llvmpipe)";
        else if (d.cudaDevice >= 0) d.name = fmt::format("NVIDIA, CUDA device {}", d.cudaDevice);
        else if (!d.driver.empty()) d.name = d.driver;
        else d.name = "unnamed device";
    }
    if (!node.empty() && d.name.find(node) == std::string::npos) d.name += " " + node;
    return d;
}

struct Opened {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLint major = 0, minor = 0;
};

// Initialises `display` and creates a current OpenGL 4.5 core context on it; `where` names it in errors.
Expected<Opened> open(EGLDisplay display, const ContextConfig& config, const std::string& where) {
    Opened o;
    o.display = display;
    if (display == EGL_NO_DISPLAY) return makeError("EGL: cannot get a display for the {}", where);
    if (!eglInitialize(display, &o.major, &o.minor))
        return makeError("EGL: eglInitialize failed on the {}: {}", where, eglErrorName(eglGetError()));
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(display);
        return makeError("EGL: desktop OpenGL API not available on the {}", where);
    }
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig eglConfig = nullptr;
    EGLint numConfigs = 0;
    const char* displayExts = eglQueryString(display, EGL_EXTENSIONS);
    const bool noConfig = hasExtension(displayExts, "EGL_KHR_no_config_context");
    if (!noConfig && (!eglChooseConfig(display, configAttribs, &eglConfig, 1, &numConfigs) || numConfigs == 0)) {
        eglTerminate(display);
        return makeError("EGL: no OpenGL config on the {}", where);
    }
    // Reset notification (issue 29 #22): a context lost to a GPU reset (a watchdog, another process's
    // fault) then says so through glGetGraphicsResetStatus, which Pipeline checks after every frame,
    // instead of rendering nothing silently. EGL 1.5's attribute; a display that refuses it gets a
    // context without (GL_RESET_NOTIFICATION_STRATEGY then reads GL_NO_RESET_NOTIFICATION).
    const bool egl15 = o.major > 1 || (o.major == 1 && o.minor >= 5);
    for (const bool robust : {egl15, false}) {
        EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_CONTEXT_OPENGL_DEBUG, config.debugOutput ? EGL_TRUE : EGL_FALSE,
                                   EGL_NONE, EGL_NONE, EGL_NONE};
        if (robust) {
            contextAttribs[8] = EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY;
            contextAttribs[9] = EGL_LOSE_CONTEXT_ON_RESET;
        }
        o.context = eglCreateContext(display, noConfig ? EGL_NO_CONFIG_KHR : eglConfig, EGL_NO_CONTEXT, contextAttribs);
        if (o.context != EGL_NO_CONTEXT || !robust) break;
        eglGetError();  // refused with the attribute: try without
    }
    if (o.context == EGL_NO_CONTEXT) {
        const EGLint err = eglGetError();
        eglTerminate(display);
        return makeError("EGL: cannot create an OpenGL 4.5 core context on the {}: {}", where, eglErrorName(err));
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, o.context)) {
        eglDestroyContext(display, o.context);
        eglTerminate(display);
        return makeError("EGL: eglMakeCurrent without surface failed on the {}", where);
    }
    return o;
}

}  // namespace

Expected<std::vector<EglDeviceDesc>> enumerateEglDevices() {
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExts) return makeError("EGL: no client extensions (is libEGL installed?)");
    std::vector<EglDeviceDesc> out;
    const std::vector<EGLDeviceEXT> devices = queryDevices();
    for (size_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], static_cast<int>(i)));
    return out;
}

Expected<std::unique_ptr<Context>> Context::createHeadless(const ContextConfig& config) {
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExts) return makeError("EGL: no client extensions (is libEGL installed?)");
    BOUNCE_TRY(const DeviceRequest request, deviceRequestFromEnvironment());
    const std::vector<EGLDeviceEXT> handles = queryDevices();
    std::vector<EglDeviceDesc> devices;
    for (size_t i = 0; i < handles.size(); ++i) devices.push_back(describe(handles[i], static_cast<int>(i)));
    BOUNCE_TRY(const std::vector<DeviceCandidate> candidates, chooseDevices(devices, request));
    // The first candidate that initialises wins; an automatic choice moves on after a failure (a GPU
    // whose driver is broken), an explicit one does not (it has one candidate).
    std::string failures;
    for (const DeviceCandidate& c : candidates) {
        const std::string where = describeCandidate(devices, c);
        EGLDisplay display = EGL_NO_DISPLAY;
        std::string platform;
        if (c.surfaceless()) {
            if (!hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
                failures += (failures.empty() ? "" : "; ") +
                            std::string("no EGL_MESA_platform_surfaceless (install libegl-mesa0)");
                continue;
            }
            display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            platform = "egl-surfaceless";
        } else {
            display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, handles[static_cast<size_t>(c.index)], nullptr);
            platform = "egl-device";
        }
        auto opened = open(display, config, where);
        if (!opened.ok()) {
            spdlog::debug("{}", opened.error().message);
            failures += (failures.empty() ? "" : "; ") + opened.error().message;
            continue;
        }
        auto ctx = std::make_unique<EglContext>(opened->display, opened->context);
        if (epoxy_gl_version() < 45)
            return makeError("EGL: context on the {} reports OpenGL {}, need 4.5", where, epoxy_gl_version());
        const std::string name = c.surfaceless() ? std::string() : devices[static_cast<size_t>(c.index)].name;
        BOUNCE_TRY_VOID(ctx->initialise(config, platform, c.index, name));
        if (!failures.empty()) spdlog::warn("EGL: {} (used the {} instead)", failures, where);
        if (auto warning = softwareFallbackWarning(ctx->info().renderer, gpuDeviceNodes())) spdlog::warn("{}", *warning);
        spdlog::debug("EGL {}.{} context on the {}: {}", opened->major, opened->minor, where, ctx->info().renderer);
        return std::unique_ptr<Context>(std::move(ctx));
    }
    return makeError("{}", failures.empty() ? std::string("EGL: no device to create a context on") : failures);
}

}  // namespace bounce::gl
