#include "app/ProcessContext.h"

#include "gpu/DeviceSelection.h"

#include <cstdlib>

#include <memory>
#include <mutex>

namespace bounce {

namespace {
std::mutex g_mutex;
std::unique_ptr<gl::Context> g_context;
}  // namespace

Expected<gl::Context*> processContext(const gl::ContextConfig& config) {
    std::unique_ptr<gl::Context>& context = g_context;
    const std::lock_guard lock(g_mutex);
    if (!context) {
        BOUNCE_TRY(context, gl::Context::createHeadless(config));
    }
    return context.get();
}

bool processContextExists() {
    const std::lock_guard lock(g_mutex);
    return g_context != nullptr;
}

Expected<void> selectGpu(const std::string& text, const std::string& source) {
    BOUNCE_TRY(const int index, gl::parseDeviceIndex(text, source));
    auto devices = gl::enumerateEglDevices();
    if (!devices.ok()) return makeError("{}: {}", source, devices.error().message);
    gl::DeviceRequest request;
    request.index = index;
    request.source = source;
    if (const char* p = std::getenv("BOUNCE_EGL_PLATFORM")) request.platform = p;
    BOUNCE_TRY_VOID(gl::chooseDevices(*devices, request));
    gl::setDeviceOverride(index);
    // Processes this one starts (sweep workers, `bounce report`) use the same device.
    ::setenv("BOUNCE_EGL_DEVICE", std::to_string(index).c_str(), 1);
    return {};
}

void releaseProcessContext() {
    const std::lock_guard lock(g_mutex);
    g_context.reset();
}

}  // namespace bounce
