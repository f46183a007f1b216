#pragma once
// OpenGL 4.5 core contexts. Headless through EGL (the device platform on a real GPU, Mesa's
// surfaceless platform on llvmpipe; gpu/DeviceSelection.h picks the device), windowed through GLFW.
// Both install synchronous KHR_debug output unless ContextConfig::debugOutput is off (measured runs:
// `render --stats`, sweeps and benchmarks, whose timings a synchronous debug context would distort).
// Every context enables seamless cube-map filtering (GL_TEXTURE_CUBE_MAP_SEAMLESS: point-light
// distance maps are filtered across face edges alike on every vendor).
#include "core/Error.h"
#include "gpu/GpuInfo.h"
#include "gpu/Objects.h"

#include <glm/vec2.hpp>

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace bounce::gl {

struct ContextConfig {
    glm::ivec2 windowSize{1280, 720};  // windowed only
    std::string title = "bounce";
    bool debugOutput = true;  // a debug context with synchronous KHR_debug output (tests, the viewer)
    bool visible = true;
};

// The context configuration of a run whose timings are recorded (`render --stats`, sweep jobs): no
// debug context, so the driver may run its own threads and the times compare with bench/.
ContextConfig measuredContextConfig();

class Context {
public:
    virtual ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // EGL headless context on the device gpu/DeviceSelection.h chooses (--gpu, BOUNCE_EGL_DEVICE,
    // BOUNCE_EGL_PLATFORM=device|surfaceless). Warns (one line) when the renderer is software although
    // the machine has GPU device nodes.
    static Expected<std::unique_ptr<Context>> createHeadless(const ContextConfig& config = {});
    static Expected<std::unique_ptr<Context>> createWindowed(const ContextConfig& config = {});

    virtual void makeCurrent() = 0;
    virtual bool headless() const = 0;
    virtual GLFWwindow* window() const { return nullptr; }
    virtual void swapBuffers() {}

    const GpuInfo& info() const { return m_info; }
    // Tests answer as another device profile would (the loop budget, per-profile refusals) on the
    // context they share; BOUNCE_PROFILE does the same for a whole process.
    void setProfileForTests(DeviceProfile profile) { m_info.profile = profile; }
    // The empty VAO that attribute-less passes bind (core profile needs one bound to draw).
    void bindEmptyVertexArray() const { m_emptyVao.bind(); }

    // GL errors and high-severity messages reported through KHR_debug since the last reset.
    static int debugErrorCount();
    static void resetDebugErrorCount();
    // The context current on this thread (bounce uses one thread per context).
    static Context* current();

protected:
    Context() = default;
    // Called by implementations once the context is current: reads GpuInfo, decides the device
    // profile (BOUNCE_PROFILE may override), clamps the limits under BOUNCE_PORTABLE_LIMITS=1.
    Expected<void> initialise(const ContextConfig& config, std::string platform, int deviceIndex = -1,
                              std::string deviceName = {});
    // Deletes the context's own GL objects; implementations call it while still current.
    void releaseObjects() { m_emptyVao = VertexArray(); }

private:
    GpuInfo m_info;
    VertexArray m_emptyVao;
};

// Formats GpuInfo for `bounce info` and run records.
std::string formatInfo(const GpuInfo& info);

// The device profile of the current context (llvmpipe without one).
DeviceProfile currentProfile();
// True when BOUNCE_PORTABLE_LIMITS is set to 1 (the portable-limits mode, gpu/PortableLimits.h).
bool portableLimitsMode();
// The one-line message of a glGetGraphicsResetStatus value ("" for GL_NO_ERROR; issue 29 #22).
std::string resetStatusMessage(GLenum status);
// Throws std::runtime_error with that message when the current context, created with reset
// notification, was lost to a GPU reset (Pipeline checks after every frame; the CLI prints one line).
void throwIfContextReset();

}  // namespace bounce::gl
