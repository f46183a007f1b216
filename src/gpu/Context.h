#pragma once
// OpenGL 4.5 core contexts. Headless through EGL (the device platform on a real GPU, Mesa's
// surfaceless platform on llvmpipe), windowed through GLFW. Both install KHR_debug output.
#include "core/Error.h"
#include "gpu/Objects.h"

#include <glm/vec2.hpp>

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace bounce::gl {

struct GpuInfo {
    std::string vendor, renderer, version, glslVersion;
    std::string platform;  // "egl-device", "egl-surfaceless", "glfw"
    int maxTextureSize = 0, max3dTextureSize = 0, maxArrayLayers = 0, maxCubeMapSize = 0;
    int maxColorAttachments = 0, maxDrawBuffers = 0;
    int maxUniformBlockSize = 0, maxShaderStorageBlockSize = 0;
    int maxComputeInvocations = 0;
    int maxComputeWorkGroupSize[3] = {0, 0, 0};
    int maxComputeWorkGroupCount[3] = {0, 0, 0};
    int maxGeometryOutputVertices = 0, maxGeometryInvocations = 0;
    int maxTransformFeedbackBuffers = 0;
    int maxImageUnits = 0, maxCombinedTextureUnits = 0;
    int timerQueryBits = 0;
    std::vector<std::pair<std::string, bool>> extensions;  // extensions techniques care about
};

struct ContextConfig {
    glm::ivec2 windowSize{1280, 720};  // windowed only
    std::string title = "bounce";
    bool debugOutput = true;
    bool visible = true;
};

class Context {
public:
    virtual ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // EGL headless context. BOUNCE_EGL_PLATFORM=device|surfaceless forces a platform.
    static Expected<std::unique_ptr<Context>> createHeadless(const ContextConfig& config = {});
    static Expected<std::unique_ptr<Context>> createWindowed(const ContextConfig& config = {});

    virtual void makeCurrent() = 0;
    virtual bool headless() const = 0;
    virtual GLFWwindow* window() const { return nullptr; }
    virtual void swapBuffers() {}

    const GpuInfo& info() const { return m_info; }
    // The empty VAO that attribute-less passes bind (core profile needs one bound to draw).
    void bindEmptyVertexArray() const { m_emptyVao.bind(); }

    // GL errors and high-severity messages reported through KHR_debug since the last reset.
    static int debugErrorCount();
    static void resetDebugErrorCount();
    // The context current on this thread (bounce uses one thread per context).
    static Context* current();

protected:
    Context() = default;
    // Called by implementations once the context is current.
    void initialise(const ContextConfig& config, std::string platform);
    // Deletes the context's own GL objects; implementations call it while still current.
    void releaseObjects() { m_emptyVao = VertexArray(); }

private:
    GpuInfo m_info;
    VertexArray m_emptyVao;
};

// Formats GpuInfo for `bounce info` and run records.
std::string formatInfo(const GpuInfo& info);

}  // namespace bounce::gl
