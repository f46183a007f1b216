// The viewer's window and input: GLFW's key events (a tap shorter than a frame still counts), the
// mouse and keys that move the camera, the wipe divider, the animation and the selected light or
// object, and the window's geometry (letterboxing, reading the back buffer).
#include "app/viewer/Viewer.h"

#include "scene/SceneEdits.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <glm/gtc/matrix_transform.hpp>

namespace bounce {

namespace {
// This frame's key presses, appended by the GLFW key callback (Viewer::initWindow).
std::vector<int> keyPresses;
}  // namespace

// The largest rectangle of aspect `aspect` (w / h) centred in `area`.
Rect letterbox(float aspect, Rect area) {
    Rect r = area;
    if (static_cast<float>(area.w) / static_cast<float>(std::max(area.h, 1)) > aspect) {
        r.w = std::max(1, static_cast<int>(std::lround(static_cast<float>(area.h) * aspect)));
        r.x = area.x + (area.w - r.w) / 2;
    } else {
        r.h = std::max(1, static_cast<int>(std::lround(static_cast<float>(area.w) / aspect)));
        r.y = area.y + (area.h - r.h) / 2;
    }
    return r;
}

// The window's back buffer in `r` as display values, row 0 at the top.
Image readWindow(Rect r) {
    Image shot(r.w, r.h);
    std::vector<float> rgb(static_cast<size_t>(r.w) * r.h * 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(r.x, r.y, r.w, r.h, GL_RGB, GL_FLOAT, rgb.data());
    for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) {
            const float* p = &rgb[(static_cast<size_t>(y) * r.w + x) * 3];
            shot.at(x, r.h - 1 - y) = {p[0], p[1], p[2]};
        }
    return shot;
}

void Viewer::initWindow() {
// Discrete keys (Tab, space, `,` `.`, F12, b) are taken from GLFW's key events, not from the key
// state once a frame: a tap shorter than a frame (llvmpipe frames take up to the frame budget, and
// xdotool's taps take microseconds) is pressed and released within one glfwPollEvents, so the
// state would never read "down". This ImGui (1.86) has no input queue either. ImGui's GLFW backend,
// installed after this, calls this callback before its own.
keyPresses.clear();
glfwSetKeyCallback(window, [](GLFWwindow*, int key, int, int action, int) {
    if (action == GLFW_PRESS) keyPresses.push_back(key);
});
IMGUI_CHECKVERSION();
ImGui::CreateContext();
ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
ImGui_ImplGlfw_InitForOpenGL(window, true);
ImGui_ImplOpenGL3_Init("#version 450");
}

void Viewer::shutdownWindow() {
ImGui_ImplOpenGL3_Shutdown();
ImGui_ImplGlfw_Shutdown();
ImGui::DestroyContext();
}

void Viewer::pollEvents() {
    keyPresses.clear();  // this frame's presses only
    glfwPollEvents();
}

// This frame's presses of `key` (from the key callback of initWindow).
int Viewer::pressCount(int key) const { return static_cast<int>(std::count(keyPresses.begin(), keyPresses.end(), key)); }

// The scene edits of scene/SceneEdits.h (shared with `import bounce`); the indices are valid by construction.
void Viewer::moveSelected(glm::vec3 delta) {
    if (selectObject) {
        if (selectedObject >= 0 && moveObject(*scene, static_cast<size_t>(selectedObject), delta).ok()) {
            // SceneGpu skips the upload when the time has not changed (a paused animation).
            for (Side* side : {&a, &b})
                if (side->pipeline) side->pipeline->sceneGpu().invalidateObjects();
        }
    } else if (!scene->lights.empty()) {
        (void)moveLight(*scene, static_cast<size_t>(selectedLight), delta);
    }
}

// Mouse and keys, unless the panel has them: camera, wipe divider, animation, the selected light or
// object, the A/B mode.
bool Viewer::handleInput(float dt) {
    ImGuiIO& io = ImGui::GetIO();
    double mx, my;
    glfwGetCursorPos(window, &mx, &my);
    const float dx = static_cast<float>(mx - lastX), dy = static_cast<float>(my - lastY);
    lastX = mx;
    lastY = my;
    const bool ctrl = glfwGetKey(window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(window, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    const glm::vec3 camForward = glm::normalize(camera.target - camera.position);
    const glm::vec3 camRight = glm::normalize(glm::cross(camForward, glm::vec3(0, 1, 0)));
    const glm::vec3 camUp = glm::cross(camRight, camForward);
    bool dragWipe = false;
    if (!io.WantCaptureMouse) {
        const float rotate = 0.005f;  // radians per pixel of mouse motion
        const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        // The wipe divider is dragged where it is (within 8 pixels of it).
        const float wipeX = static_cast<float>(lastRectA.x) + wipe * static_cast<float>(lastRectA.w);
        if (left && abMode == AbMode::Wipe && glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS) dragWipe = true;
        if (left && abMode == AbMode::Wipe && std::abs(static_cast<float>(mx) - wipeX) < 8.0f) dragWipe = true;
        if (dragWipe && lastRectA.w > 0) {
            wipe = std::clamp((static_cast<float>(mx) - static_cast<float>(lastRectA.x)) / static_cast<float>(lastRectA.w), 0.0f, 1.0f);
        } else if (left && ctrl) {
            moveSelected((camRight * dx - camUp * dy) * (controller.distance * 0.002f));
        } else if (left) {
            controller.yaw -= dx * rotate;
            controller.pitch = std::clamp(controller.pitch + dy * rotate * (controller.fly ? -1.0f : 1.0f), -1.5f, 1.5f);
        }
        if (!controller.fly && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
            const glm::vec3 f = controller.forward();
            const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
            const glm::vec3 u = glm::cross(r, f);
            controller.target += (-r * dx + u * dy) * (controller.distance * 0.002f);
        }
        if (io.MouseWheel != 0.0f) controller.distance *= std::pow(0.9f, io.MouseWheel);
    }
    bool screenshotKey = false;
    if (!io.WantCaptureKeyboard) {
        for (int i = pressCount(GLFW_KEY_TAB); i > 0; --i) {
            if (!controller.fly) controller.position = controller.target - controller.forward() * controller.distance;
            else controller.target = controller.position + controller.forward() * controller.distance;
            controller.fly = !controller.fly;
        }
        if (pressCount(GLFW_KEY_SPACE) % 2 == 1) playing = !playing;
        if (const int n = pressCount(GLFW_KEY_PERIOD); n > 0) {
            frameF = std::floor(frameF) + n;
            playing = false;
        }
        if (const int n = pressCount(GLFW_KEY_COMMA); n > 0) {
            frameF = std::max(0.0, std::floor(frameF) - n);
            playing = false;
        }
        if (pressCount(GLFW_KEY_F12) > 0) screenshotKey = true;
        if (const int n = pressCount(GLFW_KEY_B); n > 0) {
            abMode = static_cast<AbMode>((static_cast<int>(abMode) + n) % 3);
            forceMetrics = true;
        }
        const float step = 0.25f * sceneScale * dt;  // a quarter of the scene per second
        if (controller.fly) {
            const glm::vec3 f = controller.forward();
            const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
            if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) controller.position += f * step;
            if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) controller.position -= f * step;
            if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) controller.position += r * step;
            if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) controller.position -= r * step;
            if (glfwGetKey(window, GLFW_KEY_E) == GLFW_PRESS) controller.position.y += step;
            if (glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) controller.position.y -= step;
        }
        glm::vec3 move{0.0f};
        if (ImGui::IsKeyDown(ImGuiKey_LeftArrow)) move.x -= step;
        if (ImGui::IsKeyDown(ImGuiKey_RightArrow)) move.x += step;
        if (ImGui::IsKeyDown(ImGuiKey_UpArrow)) move.z -= step;
        if (ImGui::IsKeyDown(ImGuiKey_DownArrow)) move.z += step;
        if (ImGui::IsKeyDown(ImGuiKey_PageUp)) move.y += step;
        if (ImGui::IsKeyDown(ImGuiKey_PageDown)) move.y -= step;
        if (move != glm::vec3(0.0f)) moveSelected(move);
    }
    return screenshotKey;
}

}  // namespace bounce
