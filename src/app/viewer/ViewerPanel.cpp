// The viewer's panel: a fixed ImGui column left of the view. Its layout, the settings editor over
// any Configurable (the same declaration that drives --set and `bounce list`), the animation
// controls, the frame-time graph and the counters; the A/B, debug-view and camera sections belong to
// their parts (AbComparison.cpp, DebugViewBrowser.cpp, CameraPaths.cpp).
#include "app/viewer/Viewer.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>

namespace bounce {

namespace {

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

}  // namespace

void Viewer::drawPanel(uint32_t frame, bool screenshotKey) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (abMode == AbMode::Wipe && lastRectA.w > 0) {
        // The divider, drawn in window coordinates (ImGui's origin is the top left).
        const float x = static_cast<float>(lastRectA.x) + wipe * static_cast<float>(lastRectA.w);
        ImGui::GetBackgroundDrawList()->AddLine(ImVec2(x, static_cast<float>(fbh - lastRectA.y - lastRectA.h)),
                                                ImVec2(x, static_cast<float>(fbh - lastRectA.y)), IM_COL32(255, 255, 255, 200), 1.0f);
    }
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(panelWidth), static_cast<float>(fbh)));
    ImGui::Begin("bounce", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    techniqueCombo(a, "A technique");
    ImGui::RadioButton("full", &component, 0);
    ImGui::SameLine();
    ImGui::RadioButton("direct", &component, 1);
    ImGui::SameLine();
    ImGui::RadioButton("indirect", &component, 2);
    debugViewPanel();
    const glm::ivec2 shownSize = a.pipeline ? a.pipeline->size() : renderSize;
    ImGui::Text("render %dx%d%s", shownSize.x, shownSize.y,
                fixedRenderSize ? " (fixed)" : fmt::format(" (scale {:.2f})", scale).c_str());

    abPanel();
    animationPanel(frame);
    cameraPanel();
    screenshotButton(screenshotKey);
    if (!status.empty()) ImGui::TextWrapped("%s", status.c_str());
    // The frame time and counters above the (long) settings, so that they are on screen.
    frameTimePanel();
    if (ImGui::CollapsingHeader("counters", ImGuiTreeNodeFlags_DefaultOpen))
        for (const auto& [k, val] : a.stats.counters) ImGui::Text("%-28s %10.0f", k.c_str(), val);
    if (ImGui::CollapsingHeader("A settings", ImGuiTreeNodeFlags_DefaultOpen)) settingsEditor(a);
    if (showsB() && bSource == BSource::Technique && ImGui::CollapsingHeader("B settings")) settingsEditor(b);
    if (ImGui::CollapsingHeader("renderer settings")) {
        ImGuiSettingsEditor editor;
        renderSettings.visitSettings(editor);
        if (editor.changed) a.rebuild = b.rebuild = true;
    }
    if (ImGui::CollapsingHeader("viewer settings")) {
        ImGuiSettingsEditor editor;
        viewer.visitSettings(editor);
    }
    for (Side* side : {&a, &b})
        if (!side->error.empty()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s: %s", side->label.c_str(), side->error.c_str());
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Viewer::settingsEditor(Side& side) {
    if (!side.pipeline) return;
    ImGuiSettingsEditor editor;
    ImGui::PushID(side.label.c_str());
    side.pipeline->technique().visitSettings(editor);
    ImGui::PopID();
    // Settings may change allocations: rebuild with the edited values.
    if (editor.changed) {
        side.values = currentValues(side.pipeline->technique());
        side.rebuild = true;
    }
}

void Viewer::animationPanel(uint32_t frame) {
    if (ImGui::CollapsingHeader("animation", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (ImGui::Button(playing ? "pause" : "play")) playing = !playing;
        ImGui::SameLine();
        if (ImGui::Button("<")) frameF = std::max(0.0, std::floor(frameF) - 1.0), playing = false;
        ImGui::SameLine();
        if (ImGui::Button(">")) frameF = std::floor(frameF) + 1.0, playing = false;
        ImGui::SameLine();
        ImGui::TextDisabled("(space , .)");
        int scrub = static_cast<int>(frame);
        if (ImGui::SliderInt("frame", &scrub, 0, lastFrame)) {
            frameF = scrub;
            playing = false;
        }
        ImGui::SliderFloat("speed", &speed, -4.0f, 4.0f, "%.2f frames/frame");
        ImGui::Text("frame %u  t = %.3f s  (%.0f fps scene, %.2f s animated)", frame, scene->timeOfFrame(frame),
                    scene->frameRate, duration);
        int target = selectObject ? 1 : 0;
        ImGui::RadioButton("move light", &target, 0);
        ImGui::SameLine();
        ImGui::RadioButton("move object", &target, 1);
        selectObject = target == 1;
        ImGui::TextDisabled("arrows, PgUp/PgDn, ctrl + drag");
        if (!selectObject && !scene->lights.empty()) {
            ImGui::SliderInt("light", &selectedLight, 0, static_cast<int>(scene->lights.size()) - 1);
            Light& light = scene->lights[static_cast<size_t>(selectedLight)];
            ImGui::DragFloat3("position", &light.position.x, 0.01f * sceneScale);
            if (ImGui::DragFloat3("direction", &light.direction.x, 0.01f) && glm::length(light.direction) > 0.0f)
                light.direction = glm::normalize(light.direction);
        } else if (selectObject) {
            if (movableObjects.empty()) ImGui::TextDisabled("no animated objects in this scene");
            else if (ImGui::BeginCombo("object", scene->objects[static_cast<size_t>(selectedObject)].name.c_str())) {
                for (int i : movableObjects)
                    if (ImGui::Selectable(scene->objects[static_cast<size_t>(i)].name.c_str(), i == selectedObject)) selectedObject = i;
                ImGui::EndCombo();
            }
        }
    }
}

void Viewer::frameTimePanel() {
    if (ImGui::CollapsingHeader("frame time", ImGuiTreeNodeFlags_DefaultOpen)) {
        // Stacked bars: one per frame, one segment per pass ("frame", the total, is not stacked).
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        const float width = ImGui::GetContentRegionAvail().x, height = 80.0f;
        double peak = 1e-3;
        for (const auto& passes : history)
            for (const auto& p : passes)
                if (p.name == "frame") peak = std::max(peak, p.milliseconds);
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->PushClipRect(origin, ImVec2(origin.x + width, origin.y + height), true);
        dl->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(30, 30, 30, 255));
        const float barWidth = width / static_cast<float>(std::max(viewer.graphFrames, 1));
        static const ImU32 palette[] = {IM_COL32(230, 159, 0, 255),  IM_COL32(86, 180, 233, 255),
                                        IM_COL32(0, 158, 115, 255),  IM_COL32(240, 228, 66, 255),
                                        IM_COL32(0, 114, 178, 255),  IM_COL32(213, 94, 0, 255),
                                        IM_COL32(204, 121, 167, 255), IM_COL32(160, 160, 160, 255)};
        for (size_t i = 0; i < history.size(); ++i) {
            float y = origin.y + height;
            const float x = origin.x + static_cast<float>(i) * barWidth;
            for (const auto& p : history[i]) {
                // Top-level passes only: "frame" is their total and "rsm/gather" is inside "rsm".
                if (p.name == "frame" || p.name.find('/') != std::string::npos) continue;
                auto [it, inserted] = passColours.try_emplace(p.name, palette[passColours.size() % std::size(palette)]);
                const float h = static_cast<float>(p.milliseconds / peak) * height;
                dl->AddRectFilled(ImVec2(x, y - h), ImVec2(x + std::max(barWidth - 1.0f, 1.0f), y), it->second);
                y -= h;
            }
        }
        dl->PopClipRect();
        graphRect = {origin.x, origin.y, width, height};
        graphBars = history.size();
        ImGui::Dummy(ImVec2(width, height));
        ImGui::TextDisabled("peak %.1f ms GPU over %zu frames", peak, history.size());
        for (const auto& p : a.stats.passes) {
            const auto it = passColours.find(p.name);
            if (it != passColours.end()) {
                ImGui::ColorButton(p.name.c_str(), ImGui::ColorConvertU32ToFloat4(it->second), ImGuiColorEditFlags_NoTooltip, ImVec2(10, 10));
                ImGui::SameLine();
            }
            ImGui::Text("%-24s %8.3f ms", p.name.c_str(), p.milliseconds);
        }
        ImGui::Text("%-24s %8.3f ms", "cpu (frame submission)", a.stats.cpuMilliseconds);
        if (showsB() && bSource == BSource::Technique)
            ImGui::Text("B %-22s %8.3f ms", "frame (cpu)", b.stats.cpuMilliseconds);
    }
}

}  // namespace bounce
