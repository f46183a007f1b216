// Windowed OpenGL 4.5 core context through GLFW, for `bounce view`.
#include "gpu/Context.h"

#include <GLFW/glfw3.h>
#include <spdlog/spdlog.h>

namespace bounce::gl {

namespace {

class GlfwContext final : public Context {
public:
    explicit GlfwContext(GLFWwindow* window) : m_window(window) {}
    ~GlfwContext() override {
        releaseObjects();
        glfwDestroyWindow(m_window);
        glfwTerminate();
    }
    void makeCurrent() override { glfwMakeContextCurrent(m_window); }
    bool headless() const override { return false; }
    GLFWwindow* window() const override { return m_window; }
    void swapBuffers() override { glfwSwapBuffers(m_window); }
    using Context::initialise;

private:
    GLFWwindow* m_window;
};

void glfwErrorCallback(int code, const char* message) { spdlog::debug("GLFW error {}: {}", code, message); }

}  // namespace

Expected<std::unique_ptr<Context>> Context::createWindowed(const ContextConfig& config) {
    glfwSetErrorCallback(glfwErrorCallback);
    if (!glfwInit()) return makeError("GLFW: cannot initialise (no display? set DISPLAY or use `bounce render`)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, config.debugOutput ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, config.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(config.windowSize.x, config.windowSize.y, config.title.c_str(), nullptr, nullptr);
    if (!window) {
        const char* description = nullptr;
        glfwGetError(&description);
        glfwTerminate();
        return makeError("GLFW: cannot create an OpenGL 4.5 core window: {}", description ? description : "unknown");
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    auto ctx = std::make_unique<GlfwContext>(window);
    BOUNCE_TRY_VOID(ctx->initialise(config, "glfw"));
    return std::unique_ptr<Context>(std::move(ctx));
}

}  // namespace bounce::gl
