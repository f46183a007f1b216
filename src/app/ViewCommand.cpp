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
#include "app/Cli.h"
#include "app/Options.h"
#include "app/viewer/BackgroundReference.h"
#include "app/viewer/ViewerScript.h"
#include "app/viewer/ViewerSettings.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "core/ToneMap.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/Heatmap.h"
#include "scene/CameraPath.h"
#include "scene/SceneEdits.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>

namespace bounce {

namespace {

struct ViewOptions {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string technique = "direct";
    std::string size = "1280x720";
    std::string renderSize;  // fixed internal size; empty: the view's size times the adaptive scale
    std::vector<std::string> settings;
    std::string bTechnique;
    std::vector<std::string> bSettings;
    std::string reference;  // stored EXR as side B
    std::string script;
    std::string bookmarks;  // loaded at start if it exists, written by "save bookmarks"
    std::string screenshotDir = ".";
    int quitAfter = 0;  // frames; 0 = run until the window closes (automated smoke tests use it)
    std::string screenshot;  // with quitAfter: PNG of the last displayed window
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
        fly = false;
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

enum class AbMode { Off, Split, Wipe };
constexpr const char* kAbModeNames[] = {"off", "split", "wipe"};

// One side of the comparison: a technique with its own settings and pipeline.
struct Side {
    std::string label;
    std::string technique;
    std::map<std::string, std::string> values;  // technique settings applied on (re)build
    std::unique_ptr<Pipeline> pipeline;
    FrameStats stats;
    std::string error;
    bool rebuild = true;
    std::string view;          // debug view name; empty: the image (component)
    std::string settingView;   // the setting a setting-driven view changed (reset when leaving it)
    glm::ivec2 builtSize{0};   // the size of the last (re)build, successful or not
};

Expected<std::unique_ptr<Technique>> makeTechnique(const Scene& scene, const std::string& name,
                                                   const std::map<std::string, std::string>& values) {
    BOUNCE_TRY(auto technique, createTechnique(name));
    render::RenderSettings ignored;  // the scene's renderer defaults were applied once at start
    // With a context, the device profile's defaults first (core/DeviceProfile.h).
    const std::optional<DeviceProfile> profile =
        gl::Context::current() ? std::optional(gl::Context::current()->info().profile) : std::nullopt;
    BOUNCE_TRY_VOID(applyAllSettings(scene, *technique, ignored, {}, profile));
    BOUNCE_TRY_VOID(applySettings(*technique, values, fmt::format("technique '{}'", name)));
    return technique;
}

std::map<std::string, std::string> currentValues(Technique& t) {
    std::map<std::string, std::string> values;
    for (const auto& d : describeSettings(t)) values[d.name] = d.defaultValue;
    return values;
}

// RGBA32F texture holding `image` (re-created when the size changes). Image row 0 is the top.
void uploadImage(gl::Texture& texture, const std::string& label, const Image& image) {
    if (!texture || texture.width() != image.width() || texture.height() != image.height())
        texture = gl::Texture::create2D(label, image.width(), image.height(), GL_RGBA32F);
    std::vector<glm::vec4> rgba(image.pixelCount());
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            rgba[static_cast<size_t>(image.height() - 1 - y) * image.width() + x] = glm::vec4(image.at(x, y), 1.0f);
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.width(), image.height(), GL_RGBA, GL_FLOAT, rgba.data());
}

struct Rect {
    int x = 0, y = 0, w = 0, h = 0;  // GL window coordinates (origin bottom left)
};

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

struct Metrics {
    bool valid = false;
    double relMse = 0.0, flip = 0.0;
    uint32_t frame = 0;
    std::string message;  // why there are none
};

int runView(const ViewOptions& o) {
    const std::string cmd = "view";
    auto size = parseSize(o.size);
    if (!size.ok()) return failCommand(cmd, size.error().message);
    std::optional<glm::ivec2> fixedRenderSize;
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
    ViewerSettings viewer;
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
    std::vector<ScriptAction> script;
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
    auto scene = loadSceneWithParams(o.scene, o.sceneParams);
    if (!scene.ok()) return failCommand(cmd, scene.error().message);
    warnOneSidedSurfaces(*scene, fixedRenderSize.value_or(*size), 0);

    render::RenderSettings renderSettings;
    Side a, b;
    a.label = "A";
    b.label = "B";
    a.technique = o.technique;
    {
        auto t = createTechnique(a.technique);
        if (!t.ok()) return failCommand(cmd, "--technique: " + t.error().message);
        if (auto r = applyAllSettings(*scene, **t, renderSettings, techniqueSettings); !r.ok()) return failCommand(cmd, r.error().message);
        a.values = currentValues(**t);
    }
    enum class BSource { Technique, Image };
    BSource bSource = BSource::Technique;
    AbMode abMode = AbMode::Off;
    b.technique = o.bTechnique.empty() ? o.technique : o.bTechnique;
    {
        auto t = createTechnique(b.technique);
        if (!t.ok()) return failCommand(cmd, "--b-technique: " + t.error().message);
        render::RenderSettings ignored;
        if (auto r = applyAllSettings(*scene, **t, ignored, o.bSettings); !r.ok()) return failCommand(cmd, "--b-set: " + r.error().message);
        b.values = currentValues(**t);
    }
    if (!o.bTechnique.empty()) abMode = AbMode::Split;
    Image bImage;  // side B as an image: a stored EXR or the background reference
    std::string bImageName;
    if (!o.reference.empty()) {
        auto img = readImage(o.reference);
        if (!img.ok()) return failCommand(cmd, "--reference " + img.error().message);
        bImage = std::move(*img);
        bImageName = o.reference;
        bSource = BSource::Image;
        abMode = AbMode::Split;
    }
    std::vector<CameraBookmark> bookmarks;
    if (!o.bookmarks.empty() && std::filesystem::exists(o.bookmarks)) {
        auto marks = readCameraBookmarks(o.bookmarks);
        if (!marks.ok()) return failCommand(cmd, "--bookmarks " + marks.error().message);
        bookmarks = std::move(*marks);
    }

    gl::ContextConfig config;
    config.windowSize = *size;
    config.title = fmt::format("bounce view - {}", scene->name);
    auto context = gl::Context::createWindowed(config);
    if (!context.ok()) return failCommand(cmd, context.error().message);
    GLFWwindow* window = (*context)->window();
    // The settings again, now over the device profile's defaults (core/DeviceProfile.h).
    applyProfileDefaults(viewer, (*context)->info().profile);
    if (auto r = applySettings(viewer, viewerValues, "viewer"); !r.ok()) return failCommand(cmd, "--set " + r.error().message);
    for (Side* side : {&a, &b}) {
        auto t = createTechnique(side->technique);
        render::RenderSettings ignored;
        const bool isA = side == &a;
        if (auto r = applyAllSettings(*scene, **t, isA ? renderSettings : ignored, isA ? techniqueSettings : o.bSettings,
                                      (*context)->info().profile);
            !r.ok())
            return failCommand(cmd, r.error().message);
        side->values = currentValues(**t);
    }

    // app/display.frag for float textures, unsigned-integer arrays (ID views) and multisampled arrays.
    auto buildDisplay = [](const char* name, std::vector<std::pair<std::string, std::string>> defines) {
        return gl::Program::build({name, {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "app/display.frag"}},
                                   std::move(defines)});
    };
    auto display = buildDisplay("display", {});
    if (!display.ok()) return failCommand(cmd, display.error().message);
    auto displayIds = buildDisplay("display.ids", {{"DISPLAY_IDS", "1"}});
    if (!displayIds.ok()) return failCommand(cmd, displayIds.error().message);
    auto displayMs = buildDisplay("display.multisample", {{"DISPLAY_MS", "1"}});
    if (!displayMs.ok()) return failCommand(cmd, displayMs.error().message);
    auto pointsProgram = gl::Program::build({"points", {{GL_VERTEX_SHADER, "app/points.vert"}, {GL_FRAGMENT_SHADER, "app/points.frag"}}});
    if (!pointsProgram.ok()) return failCommand(cmd, pointsProgram.error().message);

    // Discrete keys (Tab, space, `,` `.`, F12, b) are taken from GLFW's key events, not from the key
    // state once a frame: a tap shorter than a frame (llvmpipe frames take up to the frame budget, and
    // xdotool's taps take microseconds) is pressed and released within one glfwPollEvents, so the
    // state would never read "down". This ImGui (1.86) has no input queue either. ImGui's GLFW backend,
    // installed after this, calls this callback before its own.
    static std::vector<int> keyPresses;
    keyPresses.clear();
    glfwSetKeyCallback(window, [](GLFWwindow*, int key, int, int action, int) {
        if (action == GLFW_PRESS) keyPresses.push_back(key);
    });
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450");

    CameraController controller;
    controller.initialise(scene->camera.at(0.0f));
    Camera camera = scene->camera;
    camera.animation = {};
    CameraPath path;
    path.scene = scene->name;
    bool followPath = false;

    gl::Texture bImageTexture, heatTexture;
    if (!bImage.empty()) uploadImage(bImageTexture, "viewer.bImage", bImage);
    BackgroundReference background;
    Metrics metrics;
    bool heatmap = false, forceMetrics = false;
    float wipe = 0.5f;
    int component = 0, layer = 0;
    bool playing = true;
    double frameF = 0.0;
    float speed = 1.0f;
    const float duration = animationDuration(*scene);
    const int lastFrame = std::max(1, static_cast<int>(std::ceil(duration * scene->frameRate)));
    // What the arrow keys and ctrl-drag move: light i or object i (animated objects only: static
    // geometry is uploaded once).
    bool selectObject = false;
    int selectedLight = 0, selectedObject = -1;
    std::vector<int> movableObjects;
    for (size_t i : bounce::movableObjects(*scene)) movableObjects.push_back(static_cast<int>(i));
    if (!movableObjects.empty()) selectedObject = movableObjects.front();
    float scale = 1.0f;
    int cooldown = 0;
    std::deque<std::vector<gl::PassTime>> history;
    std::map<std::string, ImU32> passColours;
    int shotCounter = 0;
    std::string status;
    double lastX = 0, lastY = 0, lastTime = glfwGetTime();
    glm::vec3 lo, hi;
    scene->bounds(0.0f, lo, hi);
    const float sceneScale = std::max(glm::length(hi - lo), 1e-3f);

    size_t scriptPos = 0;
    int scriptWait = 0;
    bool waitReference = false, quit = false;
    std::string waitFile;  // wait-file: until it exists or waitFileDeadline (glfwGetTime) passes
    double waitFileDeadline = 0.0;
    std::string fatal;  // a script action failed: the viewer ends with this message
    glm::vec4 graphRect{0.0f};  // the frame-time graph as last drawn: x, y, width, height (for `state`)
    size_t graphBars = 0;
    Rect viewArea, lastRectA, lastRectB;

    // This frame's presses of `key` (from the key callback above).
    auto pressCount = [&](int key) { return static_cast<int>(std::count(keyPresses.begin(), keyPresses.end(), key)); };
    // The scene edits of scene/SceneEdits.h (shared with `import bounce`); the indices are valid by construction.
    auto moveSelected = [&](glm::vec3 delta) {
        if (selectObject) {
            if (selectedObject >= 0 && moveObject(*scene, static_cast<size_t>(selectedObject), delta).ok()) {
                // SceneGpu skips the upload when the time has not changed (a paused animation).
                for (Side* side : {&a, &b})
                    if (side->pipeline) side->pipeline->sceneGpu().invalidateObjects();
            }
        } else if (!scene->lights.empty()) {
            (void)moveLight(*scene, static_cast<size_t>(selectedLight), delta);
        }
    };
    auto currentFrame = [&] { return static_cast<uint32_t>(std::max(0.0, std::floor(frameF))); };
    auto setView = [&](Side& side, const std::string& name) -> Expected<void> {
        if (!side.settingView.empty()) {
            side.values[side.settingView] = "none";
            side.settingView.clear();
            side.rebuild = true;
        }
        side.view.clear();
        if (name == "image" || name.empty()) return {};
        if (!side.pipeline) return makeError("side {} has no pipeline", side.label);
        std::string known;
        for (const DebugView& v : side.pipeline->debugViews()) {
            if (v.name == name) {
                side.view = name;
                if (!v.setting.empty()) {
                    side.values[v.setting] = v.value;
                    side.settingView = v.setting;
                    side.rebuild = true;
                }
                return {};
            }
            known += (known.empty() ? "" : ", ") + v.name;
        }
        return makeError("unknown view '{}' for technique '{}' (known: image, {})", name, side.technique, known);
    };
    auto showsB = [&] { return abMode != AbMode::Off; };
    auto readB = [&](Image& out) -> bool {
        if (bSource == BSource::Image) {
            if (bImage.empty()) return false;
            out = bImage;
            return true;
        }
        if (!b.pipeline) return false;
        out = b.pipeline->readback(static_cast<Component>(component));
        return true;
    };
    auto computeMetrics = [&] {
        metrics = {};
        metrics.frame = currentFrame();
        Image imgA, imgB;
        if (!a.pipeline || !readB(imgB)) {
            metrics.message = "no image on one side";
            return;
        }
        imgA = a.pipeline->readback(static_cast<Component>(component));
        if (imgA.width() != imgB.width() || imgA.height() != imgB.height()) {
            metrics.message = fmt::format("sizes differ: A {}x{}, B {}x{}", imgA.width(), imgA.height(), imgB.width(), imgB.height());
            return;
        }
        metrics.relMse = relativeSquaredErrorMap(imgA, imgB).mean();
        // LDR-FLIP of what is displayed: both tone-mapped with the viewer's exposure and curve,
        // decoded to linear display values as metrics/ErrorMetrics.cpp does.
        ToneMap tm{renderSettings.exposure, parseToneCurve(renderSettings.toneCurve).ok() ? *parseToneCurve(renderSettings.toneCurve) : ToneCurve::Aces};
        auto decoded = [&](const Image& radiance) {
            Image d = toDisplay(radiance, tm);
            for (glm::vec3& p : d.pixels()) p = {srgbDecode(p.r), srgbDecode(p.g), srgbDecode(p.b)};
            return d;
        };
        const ErrorMap flip = ldrFlip(decoded(imgA), decoded(imgB));
        metrics.flip = flip.mean();
        metrics.valid = true;
        Image heat(flip.width(), flip.height());
        for (int y = 0; y < flip.height(); ++y)
            for (int x = 0; x < flip.width(); ++x) heat.at(x, y) = heatmapColor(flip.at(x, y));
        uploadImage(heatTexture, "viewer.heatmap", heat);
    };
    auto writeSideImage = [&](Side& side, const std::string& file) -> Expected<void> {
        ToneMap tm{renderSettings.exposure, parseToneCurve(renderSettings.toneCurve).ok() ? *parseToneCurve(renderSettings.toneCurve) : ToneCurve::Aces};
        if (&side == &b && bSource == BSource::Image) {
            if (bImage.empty()) return makeError("side B has no image yet");
            return writeImage(file, bImage, tm);
        }
        if (!side.pipeline) return makeError("side {} has no image ({})", side.label, side.error);
        return writeImage(file, side.pipeline->readback(static_cast<Component>(component)), tm);
    };
    // The view a background reference was started for: camera, frame, lights, animated objects' moves and
    // size, as numbers compared exactly (any change, however small, is another view).
    bool referenceActive = false;  // side B is a reference that follows the view
    int referenceSpp = 0, referenceRestarts = 0;
    std::vector<float> referenceView;
    auto referenceSize = [&] { return a.pipeline ? a.pipeline->size() : glm::ivec2(256); };
    auto currentView = [&] {
        const CameraPose pose = CameraPose::of(camera);
        std::vector<float> k{pose.position.x, pose.position.y, pose.position.z, pose.target.x, pose.target.y, pose.target.z,
                             pose.up.x, pose.up.y, pose.up.z, pose.verticalFov, static_cast<float>(currentFrame()),
                             static_cast<float>(referenceSize().x), static_cast<float>(referenceSize().y)};
        for (const Light& l : scene->lights) k.insert(k.end(), {l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y, l.direction.z});
        for (int i : movableObjects) {
            const glm::mat4& m = scene->objects[static_cast<size_t>(i)].transform;
            for (int c = 0; c < 4; ++c) k.insert(k.end(), {m[c].x, m[c].y, m[c].z, m[c].w});
        }
        return k;
    };
    auto startReference = [&](int spp) {
        controller.apply(camera);
        if (followPath && !path.keys.empty()) camera = path.evaluate(scene->timeOfFrame(currentFrame())).applyTo(camera);
        referenceActive = true;
        referenceSpp = spp;
        referenceView = currentView();
        PathTracerSettings s;
        const glm::ivec2 rs = referenceSize();
        s.width = rs.x;
        s.height = rs.y;
        s.samplesPerPixel = static_cast<uint32_t>(std::max(1, spp));
        s.bounces = viewer.referenceBounces < 0 ? PathTracerSettings::kUnbounded : viewer.referenceBounces;
        s.indirectOnly = viewer.referenceIndirectOnly;
        s.threads = viewer.referenceThreads;
        s.frame = currentFrame();
        background.start(*scene, camera, s);
        bSource = BSource::Image;
        bImage = Image();
        bImageTexture = {};  // nothing shown until the first sample of this view
        bImageName = fmt::format("path-traced reference, frame {}", s.frame);
        if (abMode == AbMode::Off) abMode = AbMode::Split;
    };
    auto takeScreenshot = [&](const std::string& png, const std::string& exr) -> Expected<void> {
        if (!png.empty()) {
            BOUNCE_TRY_VOID(writeDisplayPng(png, readWindow(viewArea)));
        }
        if (!exr.empty()) {
            if (!a.pipeline) return makeError("side A has no image ({})", a.error);
            BOUNCE_TRY_VOID(writeImage(exr, a.pipeline->readback(static_cast<Component>(component))));
        }
        return {};
    };
    auto recordKey = [&] {
        controller.apply(camera);  // a script may have moved the controller since the last frame
        const float t = scene->timeOfFrame(currentFrame());
        // A key at or before an existing key's time replaces the keys from there on (re-recording).
        std::erase_if(path.keys, [&](const CameraKey& k) { return k.time >= t; });
        path.keys.push_back({t, CameraPose::of(camera)});
    };
    auto savePath = [&](const std::string& file) -> Expected<void> {
        if (path.keys.empty()) return makeError("the camera path has no keys (record some first)");
        path.lights = lightPosesOf(*scene);
        return writeCameraPath(file, path);
    };

    // One script action; returns an error message for a failed action. Output actions run after the
    // frame was drawn (runOutput), state actions before it.
    auto runAction = [&](const ScriptAction& act) -> Expected<void> {
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
    };
    // Runs script actions until one needs a frame: a wait, or an output action when `output` is false
    // (outputs run after the frame is drawn, in the second call).
    auto runScript = [&](bool output) {
        while (fatal.empty() && !quit && scriptPos < script.size() && scriptWait == 0 && !waitReference && waitFile.empty()) {
            const ScriptAction& act = script[scriptPos];
            if (findScriptAction(act.verb)->output != output) return;  // its turn is before / after a frame
            ++scriptPos;
            spdlog::debug("script {}:{}: {}", o.script, act.line, act.verb);
            if (auto r = runAction(act); !r.ok()) fatal = fmt::format("{}:{}: {}: {}", o.script, act.line, act.verb, r.error().message);
        }
    };

    int displayed = 0;
    while (!glfwWindowShouldClose(window) && !quit && fatal.empty()) {
        if (o.quitAfter > 0 && displayed >= o.quitAfter) break;
        keyPresses.clear();  // this frame's presses only
        glfwPollEvents();
        const double now = glfwGetTime();
        const float dt = static_cast<float>(now - lastTime);
        lastTime = now;
        int fbw = 0, fbh = 0;
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
        const int panelWidth = std::min(340, fbw / 2);
        viewArea = {panelWidth, 0, std::max(2, fbw - panelWidth), fbh};
        Rect sideArea = viewArea;
        if (abMode == AbMode::Split) sideArea.w = viewArea.w / 2;  // equal halves

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
        const uint32_t frame = currentFrame();
        controller.apply(camera);
        if (followPath && !path.keys.empty()) camera = path.evaluate(scene->timeOfFrame(frame)).applyTo(camera);

        // Internal size: fixed, or the side's area times the adaptive scale (multiples of 8 so that
        // small changes of the scale do not rebuild the pipelines every frame).
        glm::ivec2 renderSize;
        if (fixedRenderSize) {
            renderSize = *fixedRenderSize;
        } else {
            auto q = [&](int n) { return std::max(8, static_cast<int>(std::lround(static_cast<float>(n) * scale / 8.0f)) * 8); };
            renderSize = {q(sideArea.w), q(sideArea.h)};
        }
        for (Side* side : {&a, &b}) {
            if (side == &b && (!showsB() || bSource != BSource::Technique)) continue;
            // A failed build is retried only when something changes (settings, technique, size).
            if (!side->rebuild && side->builtSize == renderSize) continue;
            side->builtSize = renderSize;
            auto t = makeTechnique(*scene, side->technique, side->values);
            if (t.ok()) {
                auto p = Pipeline::create(*scene, std::move(*t), renderSize, renderSettings);
                if (p.ok()) {
                    // The frame loop shows times, it does not record them: read them a frame late and
                    // let the CPU queue the next frame while the GPU works (docs/gpu.md "Measured runs").
                    (*p)->setLateTimings(true);
                    side->pipeline = std::move(*p);
                    side->error.clear();
                } else {
                    side->pipeline.reset();
                    side->error = p.error().message;
                }
            } else {
                side->pipeline.reset();
                side->error = t.error().message;
            }
            if (!side->error.empty()) spdlog::error("side {}: {}", side->label, side->error);
            side->rebuild = false;
            forceMetrics = true;
        }
        // A background reference is of the view it was started for: when the camera (or the frame, a
        // light, an object, the size) changes, it restarts for the new view, and side B and the
        // metrics follow it from its first sample (the old one no longer matches side A).
        if (referenceActive && bSource == BSource::Image && currentView() != referenceView) {
            startReference(referenceSpp);
            ++referenceRestarts;
        }
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
        if (Image update; background.takeUpdate(update)) {
            bImage = std::move(update);
            uploadImage(bImageTexture, "viewer.bImage", bImage);
            forceMetrics = true;
        }
        if (showsB() && (forceMetrics || displayed % viewer.metricsInterval == 0)) {
            computeMetrics();
            forceMetrics = false;
        }

        // Draw the sides into the view, each letterboxed to its image's aspect.
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fbw, fbh);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        int curve = static_cast<int>(parseToneCurve(renderSettings.toneCurve).ok() ? *parseToneCurve(renderSettings.toneCurve) : ToneCurve::Aces);
        auto drawSide = [&](Side& side, bool isB, Rect area, std::optional<Rect> scissor) -> Rect {
            const gl::Texture* texture = nullptr;
            const DebugView* points = nullptr;  // a points view, drawn over the image
            DebugEncoding encoding = DebugEncoding::Radiance;
            float viewScale = 1.0f;
            int level = 0;
            std::vector<DebugView> views;
            if (isB && bSource == BSource::Image) {
                if (bImageTexture) texture = &bImageTexture;
            } else if (side.pipeline) {
                texture = &side.pipeline->output(static_cast<Component>(component));
                if (!side.view.empty()) views = side.pipeline->debugViews();
                for (const DebugView& v : views)
                    if (v.name == side.view) {
                        if (v.encoding == DebugEncoding::Points || v.encoding == DebugEncoding::ClusterPoints) {
                            points = &v;
                            break;
                        }
                        if (v.texture) texture = v.texture;
                        else texture = &side.pipeline->output(Component::Indirect);
                        encoding = v.encoding;
                        viewScale = v.scale;
                        level = v.level;
                        break;
                    }
            }
            if (!texture) return {};
            const Rect r = letterbox(static_cast<float>(texture->width()) / static_cast<float>(texture->height()), area);
            glViewport(r.x, r.y, r.w, r.h);
            if (scissor) {
                glEnable(GL_SCISSOR_TEST);
                glScissor(scissor->x, scissor->y, scissor->w, scissor->h);
            }
            const GLenum target = texture->desc().target;
            const bool multisample = target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
            const bool array = target == GL_TEXTURE_2D_ARRAY || multisample;
            gl::Program& program = encoding == DebugEncoding::Ids ? *displayIds : multisample ? *displayMs : *display;
            texture->bind(array ? BINDING_TEX_INPUT1 : BINDING_TEX_INPUT0);
            const bool overlay = heatmap && metrics.valid && heatTexture && side.view.empty();
            if (overlay) heatTexture.bind(BINDING_TEX_INPUT2);
            program.set("u_exposure", renderSettings.exposure);
            program.set("u_curve", curve);
            program.set("u_encoding", static_cast<int>(encoding));
            program.set("u_scale", viewScale);
            program.set("u_array", array ? 1 : 0);
            program.set("u_layer", static_cast<float>(std::clamp(layer, 0, std::max(0, texture->desc().depth - 1))));
            program.set("u_level", level);
            program.set("u_samples", texture->desc().samples);
            program.set("u_overlay", overlay ? viewer.heatmapOpacity : 0.0f);
            program.use();
            (*context)->bindEmptyVertexArray();
            glDrawArrays(GL_TRIANGLES, 0, 3);
            if (points && points->texture && points->texture->desc().target == GL_TEXTURE_2D_ARRAY) {
                const gl::TextureDesc& d = points->texture->desc();
                // The level's size as GL has it (a pyramid level halves with floor, as GL's mip chain).
                GLint w = 0, h = 0;
                glGetTextureLevelParameteriv(points->texture->id(), points->level, GL_TEXTURE_WIDTH, &w);
                glGetTextureLevelParameteriv(points->texture->id(), points->level, GL_TEXTURE_HEIGHT, &h);
                points->texture->bind(BINDING_TEX_INPUT1);
                pointsProgram->set("u_gridSize", glm::ivec2(w, h));
                pointsProgram->set("u_level", points->level);
                pointsProgram->set("u_mean", points->encoding == DebugEncoding::ClusterPoints ? 1 : 0);
                pointsProgram->set("u_clipFromWorld", render::cameraView(camera, side.pipeline->size()).clipFromWorld());
                pointsProgram->set("u_pointSize", points->scale);
                pointsProgram->use();
                glEnable(GL_PROGRAM_POINT_SIZE);
                glDrawArrays(GL_POINTS, 0, w * h * d.depth);
                glDisable(GL_PROGRAM_POINT_SIZE);
            }
            glDisable(GL_SCISSOR_TEST);
            return r;
        };
        if (abMode == AbMode::Off) {
            lastRectA = drawSide(a, false, sideArea, std::nullopt);
        } else if (abMode == AbMode::Split) {
            lastRectA = drawSide(a, false, sideArea, std::nullopt);
            Rect right = sideArea;
            right.x += sideArea.w;
            lastRectB = drawSide(b, true, right, std::nullopt);
        } else {
            // Wipe: the same rectangle, A left of the divider and B right of it.
            lastRectA = letterbox(static_cast<float>(renderSize.x) / static_cast<float>(renderSize.y), viewArea);
            const int split = lastRectA.x + static_cast<int>(std::lround(wipe * static_cast<float>(lastRectA.w)));
            drawSide(a, false, viewArea, Rect{viewArea.x, 0, split - viewArea.x, fbh});
            lastRectB = drawSide(b, true, viewArea, Rect{split, 0, viewArea.x + viewArea.w - split, fbh});
            glViewport(0, 0, fbw, fbh);
        }
        glViewport(0, 0, fbw, fbh);

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
        auto techniqueCombo = [&](Side& side, const char* label) {
            if (ImGui::BeginCombo(label, side.technique.c_str())) {
                for (const TechniqueInfo& t : registeredTechniques())
                    if (ImGui::Selectable(t.name.c_str(), t.name == side.technique)) {
                        auto tech = makeTechnique(*scene, t.name, {});
                        if (tech.ok()) {
                            side.technique = t.name;
                            side.values = currentValues(**tech);
                            side.view.clear();
                            side.settingView.clear();
                            side.rebuild = true;
                            if (&side == &b) {
                                bSource = BSource::Technique;
                                background.stop();
                                referenceActive = false;
                            }
                        }
                    }
                ImGui::EndCombo();
            }
        };
        auto settingsEditor = [&](Side& side) {
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
        };
        techniqueCombo(a, "A technique");
        ImGui::RadioButton("full", &component, 0);
        ImGui::SameLine();
        ImGui::RadioButton("direct", &component, 1);
        ImGui::SameLine();
        ImGui::RadioButton("indirect", &component, 2);
        if (a.pipeline) {
            const std::vector<DebugView> views = a.pipeline->debugViews();
            if (ImGui::BeginCombo("view", a.view.empty() ? "image" : a.view.c_str())) {
                if (ImGui::Selectable("image", a.view.empty())) (void)setView(a, "image");
                for (const DebugView& v : views)
                    if (ImGui::Selectable(v.name.c_str(), v.name == a.view)) (void)setView(a, v.name);
                ImGui::EndCombo();
            }
            for (const DebugView& v : views)
                if (v.name == a.view && v.texture && v.encoding != DebugEncoding::Points && v.encoding != DebugEncoding::ClusterPoints &&
                    (v.texture->desc().target == GL_TEXTURE_2D_ARRAY || v.texture->desc().target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY))
                    ImGui::SliderInt("layer", &layer, 0, v.texture->desc().depth - 1);
        }
        const glm::ivec2 shownSize = a.pipeline ? a.pipeline->size() : renderSize;
        ImGui::Text("render %dx%d%s", shownSize.x, shownSize.y,
                    fixedRenderSize ? " (fixed)" : fmt::format(" (scale {:.2f})", scale).c_str());

        if (ImGui::CollapsingHeader("A/B comparison", ImGuiTreeNodeFlags_DefaultOpen)) {
            int mode = static_cast<int>(abMode);
            for (int i = 0; i < 3; ++i) {
                if (i) ImGui::SameLine();
                ImGui::RadioButton(kAbModeNames[i], &mode, i);
            }
            if (mode != static_cast<int>(abMode)) {
                abMode = static_cast<AbMode>(mode);
                forceMetrics = true;
            }
            ImGui::SameLine();
            ImGui::TextDisabled("(b)");
            if (showsB()) {
                int source = static_cast<int>(bSource);
                ImGui::RadioButton("B technique", &source, 0);
                ImGui::SameLine();
                ImGui::RadioButton("B image", &source, 1);
                bSource = static_cast<BSource>(source);
                if (bSource == BSource::Technique) techniqueCombo(b, "B technique##combo");
                else ImGui::TextWrapped("%s", bImageName.empty() ? "(no image: render a reference)" : bImageName.c_str());
                if (abMode == AbMode::Wipe) ImGui::SliderFloat("wipe", &wipe, 0.0f, 1.0f);
                if (ImGui::Checkbox("FLIP heat map", &heatmap)) forceMetrics = true;
                if (metrics.valid)
                    ImGui::Text("A vs B, frame %u: relMSE %.4g  FLIP %.4f", metrics.frame, metrics.relMse, metrics.flip);
                else
                    ImGui::TextDisabled("no metrics: %s", metrics.message.c_str());
            }
            const auto progress = background.progress();
            if (ImGui::Button(progress.running ? "restart reference" : "render reference")) startReference(viewer.referenceSpp);
            if (progress.running) {
                ImGui::SameLine();
                if (ImGui::Button("stop")) {
                    background.stop();
                    referenceActive = false;  // stopped on purpose: moving the camera does not restart it
                }
            }
            if (progress.samplesTarget > 0) {
                const float fraction = static_cast<float>(progress.samplesDone) / static_cast<float>(progress.samplesTarget);
                ImGui::ProgressBar(fraction, ImVec2(-1, 0),
                                   fmt::format("{}/{} spp  {:.1f} s", progress.samplesDone, progress.samplesTarget, progress.seconds).c_str());
            }
            if (!progress.error.empty()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", progress.error.c_str());
        }
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
        if (ImGui::Button("screenshot (F12)") || screenshotKey) {
            const std::string base = (std::filesystem::path(o.screenshotDir) / fmt::format("bounce-{:04d}", shotCounter++)).string();
            auto r = takeScreenshot(base + ".png", base + ".exr");
            status = r.ok() ? "saved " + base + ".png/.exr" : r.error().message;
        }
        if (!status.empty()) ImGui::TextWrapped("%s", status.c_str());
        // The frame time and counters above the (long) settings, so that they are on screen.
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
        ++displayed;
        runScript(true);
        if (o.quitAfter > 0 && displayed == o.quitAfter && !o.screenshot.empty())
            if (auto r = writeDisplayPng(o.screenshot, readWindow({0, 0, fbw, fbh})); !r.ok()) fatal = r.error().message;
        (*context)->swapBuffers();
    }
    background.stop();
    a.pipeline.reset();
    b.pipeline.reset();
    bImageTexture = {};
    heatTexture = {};
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    if (!fatal.empty()) return failCommand(cmd, fatal);
    if (!a.pipeline && !a.error.empty() && !o.script.empty()) return failCommand(cmd, a.error);
    return 0;
}

}  // namespace

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
    c->callback([&action, o] { action = [o] { return runView(*o); }; });
}

}  // namespace bounce
