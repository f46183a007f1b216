// The viewer's camera bookmarks, the recorded camera path (JSON, scene/CameraPath.h) that
// `bounce render --camera-path` replays, and screenshots (the view as PNG, side A's radiance as EXR).
#include "app/viewer/Viewer.h"

#include "core/ImageIo.h"

#include <filesystem>

namespace bounce {

Expected<void> Viewer::takeScreenshot(const std::string& png, const std::string& exr) {
    if (!png.empty()) {
        BOUNCE_TRY_VOID(writeDisplayPng(png, readWindow(viewArea)));
    }
    if (!exr.empty()) {
        if (!a.pipeline) return makeError("side A has no image ({})", a.error);
        BOUNCE_TRY_VOID(writeImage(exr, a.pipeline->readback(static_cast<Component>(component))));
    }
    return {};
}

void Viewer::recordKey() {
    controller.apply(camera);  // a script may have moved the controller since the last frame
    const float t = scene->timeOfFrame(currentFrame());
    // A key at or before an existing key's time replaces the keys from there on (re-recording).
    std::erase_if(path.keys, [&](const CameraKey& k) { return k.time >= t; });
    path.keys.push_back({t, CameraPose::of(camera)});
}

Expected<void> Viewer::savePath(const std::string& file) {
    if (path.keys.empty()) return makeError("the camera path has no keys (record some first)");
    path.lights = lightPosesOf(*scene);
    return writeCameraPath(file, path);
}

void Viewer::cameraPanel() {
    if (ImGui::CollapsingHeader("camera")) {
        ImGui::Text("%s (tab)  position %.2f %.2f %.2f", controller.fly ? "fly" : "orbit", camera.position.x,
                    camera.position.y, camera.position.z);
        static char name[64] = "view";
        ImGui::InputText("name", name, sizeof(name));
        ImGui::SameLine();
        if (ImGui::Button("bookmark")) {
            const std::string n = name;
            std::erase_if(bookmarks, [&](const CameraBookmark& m) { return m.name == n; });
            bookmarks.push_back({n, CameraPose::of(camera)});
        }
        for (const CameraBookmark& m : bookmarks)
            if (ImGui::Button(m.name.c_str())) {
                controller.initialise(m.pose.applyTo(camera));
                break;
            }
        if (!o.bookmarks.empty() && ImGui::Button("save bookmarks")) {
            auto r = writeCameraBookmarks(o.bookmarks, bookmarks);
            status = r.ok() ? "saved " + o.bookmarks : r.error().message;
        }
        ImGui::Text("camera path: %zu keys", path.keys.size());
        if (ImGui::Button("add key")) recordKey();
        ImGui::SameLine();
        if (ImGui::Button("clear")) path.keys.clear();
        ImGui::SameLine();
        ImGui::Checkbox("follow", &followPath);
        if (ImGui::Button("save path")) {
            const std::string file = (std::filesystem::path(o.screenshotDir) / "camera-path.json").string();
            auto r = savePath(file);
            status = r.ok() ? "saved " + file : r.error().message;
        }
    }
}

void Viewer::screenshotButton(bool screenshotKey) {
    if (ImGui::Button("screenshot (F12)") || screenshotKey) {
        const std::string base = (std::filesystem::path(o.screenshotDir) / fmt::format("bounce-{:04d}", shotCounter++)).string();
        auto r = takeScreenshot(base + ".png", base + ".exr");
        status = r.ok() ? "saved " + base + ".png/.exr" : r.error().message;
    }
}

}  // namespace bounce
