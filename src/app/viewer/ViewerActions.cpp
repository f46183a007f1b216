// `bounce view --script`: runs the actions viewer/ViewerScript.h parsed, state actions before a
// frame and output actions (captures, screenshots, metrics, state) after it.
#include "app/viewer/Viewer.h"

#include "app/Options.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

namespace bounce {

    // One script action; returns an error message for a failed action. Output actions run after the
    // frame was drawn (runOutput), state actions before it.
Expected<void> Viewer::runAction(const ScriptAction& act) {
    const std::string& v = act.verb;
    const std::string arg = act.args.empty() ? "" : act.args[0];
    if (v == "technique" || v == "b-technique") {
        Side& side = v == "technique" ? a : b;
        BOUNCE_TRY(auto t, makeTechnique(*scene, arg, {}));
        side.technique = arg;
        side.values = currentValues(*t);
        side.view.clear();
        side.settingView.clear();
        side.rebuild = true;
        if (&side == &b) {
            bSource = BSource::Technique;
            background.stop();
            referenceActive = false;
        }
    } else if (v == "set" || v == "b-set") {
        Side& side = v == "set" ? a : b;
        BOUNCE_TRY(auto kv, parseAssignment(arg));
        auto values = side.values;
        values[kv.first] = kv.second;
        BOUNCE_TRY(auto check, makeTechnique(*scene, side.technique, values));
        side.values = currentValues(*check);
        side.rebuild = true;
    } else if (v == "b-reference") {
        BOUNCE_TRY(bImage, readImage(arg));
        background.stop();
        referenceActive = false;
        bImageName = arg;
        bSource = BSource::Image;
        uploadImage(bImageTexture, "viewer.bImage", bImage);
    } else if (v == "ab") {
        if (arg == "off") abMode = AbMode::Off;
        else if (arg == "split") abMode = AbMode::Split;
        else if (arg == "wipe") abMode = AbMode::Wipe;
        else return makeError("ab: '{}' is not off, split or wipe", arg);
        forceMetrics = true;
    } else if (v == "wipe") {
        wipe = std::clamp(act.number(0), 0.0f, 1.0f);
    } else if (v == "heatmap") {
        if (arg != "on" && arg != "off") return makeError("heatmap: '{}' is not on or off", arg);
        heatmap = arg == "on";
        forceMetrics = true;
    } else if (v == "component") {
        BOUNCE_TRY(auto c, parseComponent(arg));
        component = static_cast<int>(c);
    } else if (v == "view") {
        BOUNCE_TRY_VOID(setView(a, arg));
    } else if (v == "frame") {
        frameF = std::max(0.0f, std::floor(act.number(0)));
        playing = false;
    } else if (v == "play") {
        playing = true;
    } else if (v == "pause") {
        playing = false;
    } else if (v == "step") {
        frameF = std::floor(frameF) + (act.args.empty() ? 1.0 : std::floor(act.number(0)));
        playing = false;
    } else if (v == "speed") {
        speed = act.number(0);
    } else if (v == "select") {
        const size_t colon = arg.find(':');
        const std::string kind = arg.substr(0, colon);
        int index = colon == std::string::npos ? -1 : std::atoi(arg.c_str() + colon + 1);
        if (arg == "object" && !movableObjects.empty()) index = movableObjects.front();  // the first animated one
        if (kind == "light" && index >= 0 && index < static_cast<int>(scene->lights.size())) {
            selectObject = false;
            selectedLight = index;
        } else if (kind == "object" && std::find(movableObjects.begin(), movableObjects.end(), index) != movableObjects.end()) {
            selectObject = true;
            selectedObject = index;
        } else {
            return makeError("select: '{}' is not light:I (I < {}) or object:I of an animated object", arg, scene->lights.size());
        }
    } else if (v == "move") {
        moveSelected({act.number(0), act.number(1), act.number(2)});
    } else if (v == "orbit") {
        controller.fly = false;
        controller.yaw = glm::radians(act.number(0));
        controller.pitch = std::clamp(glm::radians(act.number(1)), -1.5f, 1.5f);
        if (act.number(2) <= 0.0f) return makeError("orbit: distance {} must be positive", act.number(2));
        controller.distance = act.number(2);
    } else if (v == "bookmark") {
        controller.apply(camera);
        std::erase_if(bookmarks, [&](const CameraBookmark& m) { return m.name == arg; });
        bookmarks.push_back({arg, CameraPose::of(camera)});
    } else if (v == "goto") {
        auto it = std::find_if(bookmarks.begin(), bookmarks.end(), [&](const CameraBookmark& m) { return m.name == arg; });
        if (it == bookmarks.end()) return makeError("goto: no bookmark '{}'", arg);
        controller.initialise(it->pose.applyTo(camera));
    } else if (v == "key") {
        recordKey();
    } else if (v == "reference") {
        startReference(static_cast<int>(act.number(0)));
    } else if (v == "wait") {
        scriptWait = std::max(0, static_cast<int>(act.number(0)));
    } else if (v == "wait-reference") {
        waitReference = true;
    } else if (v == "wait-file") {
        waitFile = arg;
        waitFileDeadline = glfwGetTime() + (act.args.size() > 1 ? act.number(1) : 60.0);
    } else if (v == "layer") {
        layer = std::max(0, static_cast<int>(act.number(0)));
    } else if (v == "save-path") {
        BOUNCE_TRY_VOID(savePath(arg));
    } else if (v == "save-bookmarks") {
        BOUNCE_TRY_VOID(writeCameraBookmarks(arg, bookmarks));
    } else if (v == "capture" || v == "capture-b") {
        BOUNCE_TRY_VOID(writeSideImage(v == "capture" ? a : b, arg));
    } else if (v == "screenshot") {
        const bool exr = imageFormatFor(arg).ok() && *imageFormatFor(arg) == ImageFormat::Exr;
        BOUNCE_TRY_VOID(takeScreenshot(exr ? "" : arg, exr ? arg : ""));
    } else if (v == "window-shot") {
        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        BOUNCE_TRY_VOID(writeDisplayPng(arg, readWindow({0, 0, fbw, fbh})));
    } else if (v == "metrics") {
        computeMetrics();
        if (!metrics.valid) return makeError("metrics: {}", metrics.message);
        nlohmann::json j = {{"relMse", metrics.relMse}, {"flipLdr", metrics.flip}, {"frame", metrics.frame},
                            {"a", a.technique}, {"b", bSource == BSource::Image ? bImageName : b.technique},
                            {"component", componentName(static_cast<Component>(component))}};
        BOUNCE_TRY_VOID(writeTextFileAtomic(arg, j.dump(2) + "\n"));
    } else if (v == "state") {
        controller.apply(camera);
        const glm::ivec2 rs = a.pipeline ? a.pipeline->size() : glm::ivec2(0);
        nlohmann::json j = {{"frame", currentFrame()}, {"time", scene->timeOfFrame(currentFrame())}, {"playing", playing},
                            {"speed", speed}, {"renderSize", {rs.x, rs.y}}, {"scale", scale},
                            {"ab", kAbModeNames[static_cast<int>(abMode)]}, {"a", a.technique}, {"b", b.technique},
                            {"view", a.view.empty() ? "image" : a.view}, {"pathKeys", path.keys.size()},
                            {"bookmarks", bookmarks.size()}, {"layer", layer},
                            {"camera", {camera.position.x, camera.position.y, camera.position.z}},
                            {"orbit", {{"yaw", controller.yaw}, {"pitch", controller.pitch}, {"distance", controller.distance},
                                       {"fly", controller.fly}}}};
        for (const Light& l : scene->lights) j["lights"].push_back({l.position.x, l.position.y, l.position.z});
        const auto progress = background.progress();
        j["reference"] = {{"active", referenceActive}, {"restarts", referenceRestarts}, {"running", progress.running},
                          {"samples", progress.samplesDone}};
        // The frame-time graph as last drawn (window pixels, origin top left) and its bars.
        j["graph"] = {{"rect", {graphRect.x, graphRect.y, graphRect.z, graphRect.w}}, {"frames", graphBars}};
        BOUNCE_TRY_VOID(writeTextFileAtomic(arg, j.dump(2) + "\n"));
    } else if (v == "quit") {
        quit = true;
    }
    return {};
}

    // Runs script actions until one needs a frame: a wait, or an output action when `output` is false
    // (outputs run after the frame is drawn, in the second call).
void Viewer::runScript(bool output) {
    while (fatal.empty() && !quit && scriptPos < script.size() && scriptWait == 0 && !waitReference && waitFile.empty()) {
        const ScriptAction& act = script[scriptPos];
        if (findScriptAction(act.verb)->output != output) return;  // its turn is before / after a frame
        ++scriptPos;
        spdlog::debug("script {}:{}: {}", o.script, act.line, act.verb);
        if (auto r = runAction(act); !r.ok()) fatal = fmt::format("{}:{}: {}: {}", o.script, act.line, act.verb, r.error().message);
    }
}

}  // namespace bounce
