// `bounce view`: an interactive GLFW window over the same Pipeline as `bounce render`, laid out as a
// lab bench (docs/viewer.md): a fixed panel on the left, the view on the right, where the image keeps
// its aspect (letterboxed) whatever the window's shape.
//
// - A/B: side B is a second technique with its own settings, a stored EXR (--reference), or the
//   background path-traced reference of the current view (app/viewer/BackgroundReference.h); shown
//   side by side or as a wipe, same camera and scene time, with relMSE and FLIP of A against B
//   (recomputed every viewer.metricsInterval frames on the CPU) and an optional FLIP heat map.
//   A background reference restarts whenever the view it was started for changes.
// - Debug views: the Pipeline's and the technique's (Technique::debugViews), one list; discrete keys
//   act on GLFW key events (a tap shorter than a frame still counts).
// - Animation: play / pause / step / scrub / speed; the selected light or animated object moves with
//   the arrow keys and PageUp/PageDown, or ctrl + left drag in the view.
// - Camera: orbit (left drag rotates about the target, right drag pans, wheel zooms) or fly (Tab
//   toggles; WASD/QE move, left drag looks); bookmarks and a recorded camera path (JSON,
//   scene/CameraPath.h) that `bounce render --camera-path` replays.
// - Frame-time graph of the last viewer.graphFrames frames, passes stacked; the technique's counters.
// - Screenshots (F12 or the button): the view as PNG and side A's radiance as EXR.
// - Responsiveness: without --render-size, the internal size shrinks when a frame takes longer than
//   viewer.frameBudgetMs and grows back when it is well under; the display upscales.
// - --script FILE runs a list of actions (app/viewer/ViewerScript.h): the tests drive the viewer so.
//
// The viewer's parts are app/viewer/ (Viewer.h lists them); this file keeps the command: its options,
// their checks, the setup and the frame loop.
#include "app/Cli.h"
#include "app/Options.h"
#include "app/viewer/Viewer.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "gpu/Context.h"
#include "scene/SceneEdits.h"
#include "techniques/Registry.h"

#include <GLFW/glfw3.h>
#include <spdlog/spdlog.h>

#include <filesystem>

namespace bounce {

namespace {

// The last key time of every animation track in the scene (0 when nothing moves).
float animationDuration(const Scene& scene) {
    float end = 0.0f;
    auto track = [&](const TransformTrack& t) {
        if (!t.empty()) end = std::max(end, t.keys.back().time);
    };
    for (const Object& o : scene.objects) track(o.animation);
    for (const Light& l : scene.lights) track(l.animation);
    track(scene.camera.animation);
    return end;
}

}  // namespace

int Viewer::run() {
    const std::string cmd = "view";
    auto size = parseSize(o.size);
    if (!size.ok()) return failCommand(cmd, size.error().message);
    if (!o.renderSize.empty()) {
        auto rs = parseSize(o.renderSize);
        if (!rs.ok()) {
            std::string message = rs.error().message;  // parseSize names --size
            if (message.rfind("--size", 0) == 0) message.replace(0, 6, "--render-size");
            return failCommand(cmd, message);
        }
        fixedRenderSize = *rs;
    }
    // --set viewer.NAME goes to the viewer's settings, the rest to the technique and renderer.
    std::vector<std::string> techniqueSettings;
    std::map<std::string, std::string> viewerValues;
    {
        for (const std::string& s : o.settings) {
            if (s.rfind("viewer.", 0) == 0) {
                auto kv = parseAssignment(s.substr(7));
                if (!kv.ok()) return failCommand(cmd, "--set: " + kv.error().message);
                viewerValues[kv->first] = kv->second;
            } else {
                techniqueSettings.push_back(s);
            }
        }
        if (auto r = applySettings(viewer, viewerValues, "viewer"); !r.ok()) return failCommand(cmd, "--set " + r.error().message);
    }
    if (!o.script.empty()) {
        auto s = readViewerScript(o.script);
        if (!s.ok()) return failCommand(cmd, "--script " + s.error().message);
        script = std::move(*s);
    }
    if (!o.screenshotDir.empty() && !std::filesystem::is_directory(o.screenshotDir))
        return failCommand(cmd, fmt::format("--screenshot-dir '{}' is not a directory", o.screenshotDir));
    // The screenshot is written after the window has shown its frames: its path is checked before.
    if (!o.screenshot.empty()) {
        if (auto f = imageFormatFor(o.screenshot); !f.ok() || *f != ImageFormat::Png)
            return failCommand(cmd, fmt::format("--screenshot {}: screenshots are written as .png", o.screenshot));
        if (auto w = checkWritable(o.screenshot); !w.ok()) return failCommand(cmd, "--screenshot " + w.error().message);
    }
    auto loaded = loadSceneWithParams(o.scene, o.sceneParams);
    if (!loaded.ok()) return failCommand(cmd, loaded.error().message);
    scene = std::move(*loaded);
    warnOneSidedSurfaces(*scene, fixedRenderSize.value_or(*size), 0);

    a.label = "A";
    b.label = "B";
    a.technique = o.technique;
    {
        auto t = createTechnique(a.technique);
        if (!t.ok()) return failCommand(cmd, "--technique: " + t.error().message);
        if (auto r = applyAllSettings(*scene, **t, renderSettings, techniqueSettings); !r.ok()) return failCommand(cmd, r.error().message);
        a.values = currentValues(**t);
    }
    b.technique = o.bTechnique.empty() ? o.technique : o.bTechnique;
    {
        auto t = createTechnique(b.technique);
        if (!t.ok()) return failCommand(cmd, "--b-technique: " + t.error().message);
        render::RenderSettings ignored;
        if (auto r = applyAllSettings(*scene, **t, ignored, o.bSettings); !r.ok()) return failCommand(cmd, "--b-set: " + r.error().message);
        b.values = currentValues(**t);
    }
    if (!o.bTechnique.empty()) abMode = AbMode::Split;
    if (!o.reference.empty()) {
        auto img = readImage(o.reference);
        if (!img.ok()) return failCommand(cmd, "--reference " + img.error().message);
        bImage = std::move(*img);
        bImageName = o.reference;
        bSource = BSource::Image;
        abMode = AbMode::Split;
    }
    if (!o.bookmarks.empty() && std::filesystem::exists(o.bookmarks)) {
        auto marks = readCameraBookmarks(o.bookmarks);
        if (!marks.ok()) return failCommand(cmd, "--bookmarks " + marks.error().message);
        bookmarks = std::move(*marks);
    }

    gl::ContextConfig config;
    config.windowSize = *size;
    config.title = fmt::format("bounce view - {}", scene->name);
    auto windowed = gl::Context::createWindowed(config);
    if (!windowed.ok()) return failCommand(cmd, windowed.error().message);
    context = std::move(*windowed);
    window = context->window();
    // The settings again, now over the device profile's defaults (core/DeviceProfile.h).
    applyProfileDefaults(viewer, context->info().profile);
    if (auto r = applySettings(viewer, viewerValues, "viewer"); !r.ok()) return failCommand(cmd, "--set " + r.error().message);
    for (Side* side : {&a, &b}) {
        auto t = createTechnique(side->technique);
        render::RenderSettings ignored;
        const bool isA = side == &a;
        if (auto r = applyAllSettings(*scene, **t, isA ? renderSettings : ignored, isA ? techniqueSettings : o.bSettings,
                                      context->info().profile);
            !r.ok())
            return failCommand(cmd, r.error().message);
        side->values = currentValues(**t);
    }
    if (auto r = buildDisplayPrograms(); !r.ok()) return failCommand(cmd, r.error().message);
    initWindow();

    controller.initialise(scene->camera.at(0.0f));
    camera = scene->camera;
    camera.animation = {};
    path.scene = scene->name;

    if (!bImage.empty()) uploadImage(bImageTexture, "viewer.bImage", bImage);
    duration = animationDuration(*scene);
    lastFrame = std::max(1, static_cast<int>(std::ceil(duration * scene->frameRate)));
    for (size_t i : bounce::movableObjects(*scene)) movableObjects.push_back(static_cast<int>(i));
    if (!movableObjects.empty()) selectedObject = movableObjects.front();
    lastTime = glfwGetTime();
    glm::vec3 lo, hi;
    scene->bounds(0.0f, lo, hi);
    sceneScale = std::max(glm::length(hi - lo), 1e-3f);

    while (!glfwWindowShouldClose(window) && !quit && fatal.empty()) {
        if (o.quitAfter > 0 && displayed >= o.quitAfter) break;
        pollEvents();  // this frame's presses only
        const double now = glfwGetTime();
        const float dt = static_cast<float>(now - lastTime);
        lastTime = now;
        fbw = fbh = 0;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        if (fbw <= 0 || fbh <= 0) continue;  // minimised
        if (scriptWait > 0) --scriptWait;
        if (waitReference && !background.progress().running) waitReference = false;
        if (!waitFile.empty()) {
            if (std::filesystem::exists(waitFile)) waitFile.clear();
            else if (now > waitFileDeadline) fatal = fmt::format("{}: wait-file: {} did not appear in time", o.script, waitFile);
        }
        runScript(false);
        if (quit || !fatal.empty()) break;

        // Layout: the panel is a fixed column on the left; the view is the rest, never under it.
        panelWidth = std::min(340, fbw / 2);
        viewArea = {panelWidth, 0, std::max(2, fbw - panelWidth), fbh};
        sideArea = viewArea;
        if (abMode == AbMode::Split) sideArea.w = viewArea.w / 2;  // equal halves

        const bool screenshotKey = handleInput(dt);
        const uint32_t frame = currentFrame();
        controller.apply(camera);
        if (followPath && !path.keys.empty()) camera = path.evaluate(scene->timeOfFrame(frame)).applyTo(camera);

        // Internal size: fixed, or the side's area times the adaptive scale (multiples of 8 so that
        // small changes of the scale do not rebuild the pipelines every frame).
        if (fixedRenderSize) {
            renderSize = *fixedRenderSize;
        } else {
            auto q = [&](int n) { return std::max(8, static_cast<int>(std::lround(static_cast<float>(n) * scale / 8.0f)) * 8); };
            renderSize = {q(sideArea.w), q(sideArea.h)};
        }
        rebuildSides();
        followReference();
        if (a.pipeline) a.stats = a.pipeline->renderFrame(frame, &camera);
        if (showsB() && bSource == BSource::Technique && b.pipeline) b.stats = b.pipeline->renderFrame(frame, &camera);
        if (playing) {
            frameF += speed;
            if (duration > 0.0f && frameF > lastFrame) frameF = std::fmod(frameF, static_cast<double>(lastFrame));
            if (frameF < 0.0) frameF = 0.0;
        }
        if (a.pipeline) {
            history.push_back(a.stats.passes);
            while (static_cast<int>(history.size()) > viewer.graphFrames) history.pop_front();
        }
        // Adaptive internal size: shrink by a quarter while over budget, grow back below 40 % of it;
        // a cool-down of a few frames lets the new size show its time before the next change.
        if (!fixedRenderSize && viewer.frameBudgetMs > 0.0f && a.pipeline && cooldown-- <= 0) {
            // With late timings a frame's cost is its submission (CPU) or the GPU's time for the previous
            // frame, whichever is longer.
            auto frameMs = [](const FrameStats& st) {
                const double gpu = st.passes.empty() ? 0.0 : st.passes.front().milliseconds;
                return std::max(st.cpuMilliseconds, gpu);
            };
            const double ms = frameMs(a.stats) + (showsB() ? frameMs(b.stats) : 0.0);
            if (ms > viewer.frameBudgetMs && scale > viewer.minScale) {
                scale = std::max(viewer.minScale, scale * 0.75f);
                cooldown = 5;
            } else if (ms < 0.4 * viewer.frameBudgetMs && scale < 1.0f) {
                scale = std::min(1.0f, scale / 0.75f);
                cooldown = 5;
            }
        }
        takeReferenceUpdate();
        if (showsB() && (forceMetrics || displayed % viewer.metricsInterval == 0)) {
            computeMetrics();
            forceMetrics = false;
        }

        drawSides();
        drawPanel(frame, screenshotKey);
        ++displayed;
        runScript(true);
        if (o.quitAfter > 0 && displayed == o.quitAfter && !o.screenshot.empty())
            if (auto r = writeDisplayPng(o.screenshot, readWindow({0, 0, fbw, fbh})); !r.ok()) fatal = r.error().message;
        context->swapBuffers();
    }
    background.stop();
    a.pipeline.reset();
    b.pipeline.reset();
    bImageTexture = {};
    heatTexture = {};
    shutdownWindow();
    if (!fatal.empty()) return failCommand(cmd, fatal);
    if (!a.pipeline && !a.error.empty() && !o.script.empty()) return failCommand(cmd, a.error);
    return 0;
}

void registerViewCommand(CLI::App& root, CommandAction& action) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* c = root.add_subcommand("view", "interactive viewer (GLFW window): A/B comparison, debug views, animation, camera paths");
    c->add_option("--scene", o->scene, "built-in scene name or scene/model file")->required();
    c->add_option("--scene-param", o->sceneParams, "built-in scene parameter name=value (repeatable)");
    c->add_option("--technique", o->technique, "side A's technique")->capture_default_str();
    c->add_option("--size", o->size, "window size WIDTHxHEIGHT")->capture_default_str();
    c->add_option("--render-size", o->renderSize, "fixed internal render size WIDTHxHEIGHT (default: the view's size, reduced over viewer.frameBudgetMs)");
    c->add_option("--set", o->settings, "setting name=value: side A's technique, renderer.NAME, viewer.NAME (repeatable)");
    c->add_option("--b-technique", o->bTechnique, "side B's technique (opens the A/B split)");
    c->add_option("--b-set", o->bSettings, "setting name=value of side B's technique (repeatable)");
    c->add_option("--reference", o->reference, "stored image (EXR radiance) as side B");
    c->add_option("--script", o->script, "run the viewer actions in this file (docs/viewer.md)");
    c->add_option("--bookmarks", o->bookmarks, "camera bookmarks JSON: loaded if it exists, written by 'save bookmarks'");
    c->add_option("--screenshot-dir", o->screenshotDir, "folder for F12 screenshots and the saved camera path")->capture_default_str();
    c->add_option("--quit-after", o->quitAfter, "close after this many frames (0: run until closed)");
    c->add_option("--screenshot", o->screenshot, "with --quit-after: save the last frame's window as PNG");
    c->callback([&action, o] { action = [o] { return Viewer(*o).run(); }; });
}

}  // namespace bounce
