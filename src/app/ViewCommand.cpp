// `bounce view`: an interactive GLFW window over the same Pipeline as `bounce render`.
// Camera: orbit (left drag rotates about the target, right drag pans, wheel zooms) or fly (Tab
// toggles; WASD/QE move, left drag looks). Light: the selected light moves with the arrow keys
// (x/z) and PageUp/PageDown (y), or by dragging its fields in the panel. Space pauses animation.
// Techniques, components, exposure and every setting are switchable at run time in the panel.
#include "app/Cli.h"
#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/ToneMap.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <glm/gtc/constants.hpp>
#include <imgui.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {

struct ViewOptions {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string technique = "direct";
    std::string size = "1024x768";
    std::vector<std::string> settings;
    int quitAfter = 0;  // frames; 0 = run until the window closes (automated smoke tests use it)
    std::string screenshot;  // with quitAfter: PNG of the last displayed frame
};

// ImGui widgets for any Configurable: the same declaration that drives --set and `bounce list`.
class ImGuiSettingsEditor final : public SettingsVisitor {
public:
    bool changed = false;
    void field(std::string_view n, bool& v, std::string_view doc) override {
        changed |= ImGui::Checkbox(std::string(n).c_str(), &v);
        tooltip(doc);
    }
    void field(std::string_view n, int& v, std::string_view doc, int lo, int hi) override {
        changed |= ImGui::DragInt(std::string(n).c_str(), &v, 1.0f, lo, hi);
        tooltip(doc);
    }
    void field(std::string_view n, float& v, std::string_view doc, float lo, float hi) override {
        changed |= ImGui::DragFloat(std::string(n).c_str(), &v, std::max(std::abs(v) * 0.01f, 1e-3f), lo, hi, "%.4g");
        tooltip(doc);
    }
    void field(std::string_view n, std::string& v, std::string_view doc, std::span<const std::string_view> c) override {
        if (ImGui::BeginCombo(std::string(n).c_str(), v.c_str())) {
            for (auto choice : c)
                if (ImGui::Selectable(std::string(choice).c_str(), v == choice)) {
                    v = std::string(choice);
                    changed = true;
                }
            ImGui::EndCombo();
        }
        tooltip(doc);
    }

private:
    static void tooltip(std::string_view doc) {
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(doc).c_str());
    }
};

struct CameraController {
    bool fly = false;
    glm::vec3 target{0.0f};
    float distance = 1.0f, yaw = 0.0f, pitch = 0.0f;
    glm::vec3 position{0.0f};

    void initialise(const Camera& c) {
        target = c.target;
        position = c.position;
        const glm::vec3 d = c.position - c.target;
        distance = glm::length(d);
        yaw = std::atan2(d.x, d.z);
        pitch = std::asin(std::clamp(d.y / std::max(distance, 1e-6f), -1.0f, 1.0f));
    }
    glm::vec3 forward() const {
        return -glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    }
    void apply(Camera& c) const {
        if (fly) {
            c.position = position;
            c.target = position + forward();
        } else {
            c.position = target - forward() * distance;
            c.target = target;
        }
        c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    }
};

int runView(const ViewOptions& o) {
    const std::string cmd = "view";
    auto size = parseSize(o.size);
    if (!size.ok()) return failCommand(cmd, size.error().message);
    auto scene = loadSceneWithParams(o.scene, o.sceneParams);
    if (!scene.ok()) return failCommand(cmd, scene.error().message);
    gl::ContextConfig config;
    config.windowSize = *size;
    config.title = fmt::format("bounce view - {}", scene->name);
    auto context = gl::Context::createWindowed(config);
    if (!context.ok()) return failCommand(cmd, context.error().message);
    GLFWwindow* window = (*context)->window();

    auto display = gl::Program::build({"display", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                    {GL_FRAGMENT_SHADER, "app/display.frag"}}});
    if (!display.ok()) return failCommand(cmd, display.error().message);

    std::string techniqueName = o.technique;
    render::RenderSettings renderSettings;
    std::unique_ptr<Technique> pendingTechnique;
    {
        auto t = createTechnique(techniqueName);
        if (!t.ok()) return failCommand(cmd, "--technique: " + t.error().message);
        if (auto r = applyAllSettings(*scene, **t, renderSettings, o.settings); !r.ok()) return failCommand(cmd, r.error().message);
        pendingTechnique = std::move(*t);
    }

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450");

    CameraController controller;
    controller.initialise(scene->camera.at(0.0f));
    Camera camera = scene->camera;
    camera.animation = {};
    std::unique_ptr<Pipeline> pipeline;
    glm::ivec2 pipelineSize{0};
    bool rebuild = true, playing = true;
    uint32_t frame = 0;
    int component = 0, selectedLight = 0;
    double lastX = 0, lastY = 0, lastTime = glfwGetTime();
    FrameStats lastStats;
    std::string lastError;

    int displayed = 0;
    while (!glfwWindowShouldClose(window)) {
        if (o.quitAfter > 0 && displayed >= o.quitAfter) break;
        glfwPollEvents();
        const double now = glfwGetTime();
        const float dt = static_cast<float>(now - lastTime);
        lastTime = now;
        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        if (fbw <= 0 || fbh <= 0) continue;  // minimised

        ImGuiIO& io = ImGui::GetIO();
        double mx, my;
        glfwGetCursorPos(window, &mx, &my);
        const float dx = static_cast<float>(mx - lastX), dy = static_cast<float>(my - lastY);
        lastX = mx;
        lastY = my;
        glm::vec3 lo, hi;
        scene->bounds(0.0f, lo, hi);
        const float sceneScale = std::max(glm::length(hi - lo), 1e-3f);
        if (!io.WantCaptureMouse) {
            const float rotate = 0.005f;  // radians per pixel of mouse motion
            if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
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
        if (!io.WantCaptureKeyboard) {
            if (ImGui::IsKeyPressed(ImGuiKey_Tab)) {
                if (!controller.fly) controller.position = controller.target - controller.forward() * controller.distance;
                else controller.target = controller.position + controller.forward() * controller.distance;
                controller.fly = !controller.fly;
            }
            if (ImGui::IsKeyPressed(ImGuiKey_Space)) playing = !playing;
            const float speed = 0.25f * sceneScale * dt;  // a quarter of the scene per second
            if (controller.fly) {
                const glm::vec3 f = controller.forward();
                const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
                if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) controller.position += f * speed;
                if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) controller.position -= f * speed;
                if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) controller.position += r * speed;
                if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) controller.position -= r * speed;
                if (glfwGetKey(window, GLFW_KEY_E) == GLFW_PRESS) controller.position.y += speed;
                if (glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) controller.position.y -= speed;
            }
            if (!scene->lights.empty()) {
                Light& light = scene->lights[static_cast<size_t>(selectedLight)];
                if (ImGui::IsKeyDown(ImGuiKey_LeftArrow)) light.position.x -= speed;
                if (ImGui::IsKeyDown(ImGuiKey_RightArrow)) light.position.x += speed;
                if (ImGui::IsKeyDown(ImGuiKey_UpArrow)) light.position.z -= speed;
                if (ImGui::IsKeyDown(ImGuiKey_DownArrow)) light.position.z += speed;
                if (ImGui::IsKeyDown(ImGuiKey_PageUp)) light.position.y += speed;
                if (ImGui::IsKeyDown(ImGuiKey_PageDown)) light.position.y -= speed;
            }
        }
        controller.apply(camera);

        if (rebuild || pipelineSize != glm::ivec2(fbw, fbh)) {
            std::unique_ptr<Technique> technique = std::move(pendingTechnique);
            if (!technique) {
                auto t = createTechnique(techniqueName);
                if (t.ok()) technique = std::move(*t);
            }
            if (technique) {
                auto p = Pipeline::create(*scene, std::move(technique), {fbw, fbh}, renderSettings);
                if (p.ok()) {
                    pipeline = std::move(*p);
                    lastError.clear();
                } else {
                    lastError = p.error().message;
                    spdlog::error("{}", lastError);
                }
            }
            pipelineSize = {fbw, fbh};
            rebuild = false;
        }
        if (pipeline) lastStats = pipeline->renderFrame(frame, &camera);
        if (playing) ++frame;

        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fbw, fbh);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        if (pipeline) {
            pipeline->output(static_cast<Component>(component)).bind(BINDING_TEX_INPUT0);
            display->set("u_exposure", renderSettings.exposure);
            display->set("u_curve", static_cast<int>(parseToneCurve(renderSettings.toneCurve).ok()
                                                         ? *parseToneCurve(renderSettings.toneCurve)
                                                         : ToneCurve::Aces));
            display->use();
            (*context)->bindEmptyVertexArray();
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::Begin("bounce");
        if (ImGui::BeginCombo("technique", techniqueName.c_str())) {
            for (const TechniqueInfo& t : registeredTechniques())
                if (ImGui::Selectable(t.name.c_str(), t.name == techniqueName)) {
                    techniqueName = t.name;
                    rebuild = true;
                }
            ImGui::EndCombo();
        }
        ImGui::RadioButton("full", &component, 0);
        ImGui::SameLine();
        ImGui::RadioButton("direct", &component, 1);
        ImGui::SameLine();
        ImGui::RadioButton("indirect", &component, 2);
        ImGui::Checkbox("play animation (space)", &playing);
        ImGui::Text("frame %u  t = %.2f s  camera: %s (tab)", frame, scene->timeOfFrame(frame),
                    controller.fly ? "fly" : "orbit");
        if (!scene->lights.empty()) {
            const int lightCount = static_cast<int>(scene->lights.size());
            ImGui::SliderInt("light (arrows, PgUp/PgDn)", &selectedLight, 0, lightCount - 1);
            Light& light = scene->lights[static_cast<size_t>(selectedLight)];
            ImGui::DragFloat3("light position", &light.position.x, 0.01f * sceneScale);
            if (ImGui::DragFloat3("light direction", &light.direction.x, 0.01f) && glm::length(light.direction) > 0.0f)
                light.direction = glm::normalize(light.direction);
        }
        if (ImGui::CollapsingHeader("technique settings", ImGuiTreeNodeFlags_DefaultOpen) && pipeline) {
            ImGuiSettingsEditor editor;
            pipeline->technique().visitSettings(editor);
            if (editor.changed) {
                // Settings may change allocations: rebuild with the edited technique.
                auto edited = createTechnique(techniqueName);
                if (edited.ok()) {
                    (void)applySettings(**edited, [&] {
                        std::map<std::string, std::string> values;
                        for (const auto& d : describeSettings(pipeline->technique())) values[d.name] = d.defaultValue;
                        return values;
                    }(), techniqueName);
                    pendingTechnique = std::move(*edited);
                    rebuild = true;
                }
            }
        }
        if (ImGui::CollapsingHeader("renderer settings")) {
            ImGuiSettingsEditor editor;
            renderSettings.visitSettings(editor);
            if (editor.changed) rebuild = true;
        }
        if (ImGui::CollapsingHeader("GPU time (ms)", ImGuiTreeNodeFlags_DefaultOpen)) {
            for (const auto& p : lastStats.passes) ImGui::Text("%-28s %8.3f", p.name.c_str(), p.milliseconds);
            for (const auto& [k, v] : lastStats.counters) ImGui::Text("%-28s %10.0f", k.c_str(), v);
        }
        if (!lastError.empty()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", lastError.c_str());
        ImGui::End();
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        ++displayed;
        if (o.quitAfter > 0 && displayed == o.quitAfter && !o.screenshot.empty()) {
            Image shot(fbw, fbh);
            std::vector<float> rgb(static_cast<size_t>(fbw) * fbh * 3);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glReadPixels(0, 0, fbw, fbh, GL_RGB, GL_FLOAT, rgb.data());
            for (int y = 0; y < fbh; ++y)
                for (int x = 0; x < fbw; ++x) {
                    const float* p = &rgb[(static_cast<size_t>(y) * fbw + x) * 3];
                    shot.at(x, fbh - 1 - y) = {p[0], p[1], p[2]};
                }
            if (auto r = writeDisplayPng(o.screenshot, shot); !r.ok()) return failCommand(cmd, r.error().message);
        }
        (*context)->swapBuffers();
    }
    pipeline.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 0;
}

}  // namespace

void registerViewCommand(CLI::App& root, CommandAction& action) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* c = root.add_subcommand("view", "interactive viewer (GLFW window): camera, light, technique switching");
    c->add_option("--scene", o->scene, "built-in scene name or scene/model file")->required();
    c->add_option("--scene-param", o->sceneParams, "built-in scene parameter name=value (repeatable)");
    c->add_option("--technique", o->technique, "initial technique")->capture_default_str();
    c->add_option("--size", o->size, "window size WIDTHxHEIGHT")->capture_default_str();
    c->add_option("--set", o->settings, "setting name=value (repeatable)");
    c->add_option("--quit-after", o->quitAfter, "close after this many frames (0: run until closed)");
    c->add_option("--screenshot", o->screenshot, "with --quit-after: save the last frame's window as PNG");
    c->callback([&action, o] { action = [o] { return runView(*o); }; });
}

}  // namespace bounce
