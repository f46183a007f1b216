#pragma once
// `bounce view`'s state and its parts (docs/viewer.md, docs/architecture.md "The viewer"). One
// Viewer holds what the frame loop shares; its member functions live in the file of the part they
// belong to, each with one reason to change:
//
// - app/ViewCommand.cpp: the command (options, their checks, setup) and the frame loop.
// - viewer/ViewerWindow.cpp: window and input (GLFW key events, mouse and keys to camera, wipe,
//   animation and the selected light or object), letterboxing, reading the window back.
// - viewer/AbComparison.cpp: the A/B state: the sides' techniques and pipelines, side B as an image
//   or a background reference that follows the view, the relMSE/FLIP metrics and their heat map.
// - viewer/DebugViewBrowser.cpp: the debug views (Pipeline's and Technique::debugViews) and the
//   display programs that draw a side's image or view into the window.
// - viewer/CameraPaths.cpp: bookmarks, the recorded camera path, screenshots.
// - viewer/ViewerPanel.cpp: the ImGui panel's layout and the generic widgets (settings editor,
//   animation, frame-time graph, counters).
// - viewer/ViewerActions.cpp: `--script` actions (viewer/ViewerScript.h parses them).
// - viewer/BackgroundReference.h: the path tracer on a worker thread.
#include "app/viewer/BackgroundReference.h"
#include "app/viewer/ViewerScript.h"
#include "app/viewer/ViewerSettings.h"
#include "core/Error.h"
#include "core/Image.h"
#include "gpu/Context.h"
#include "gpu/Objects.h"
#include "gpu/Program.h"
#include "render/RenderSettings.h"
#include "scene/CameraPath.h"
#include "scene/Scene.h"
#include "techniques/Pipeline.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace bounce {

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

struct Metrics {
    bool valid = false;
    double relMse = 0.0, flip = 0.0;
    uint32_t frame = 0;
    std::string message;  // why there are none
};

struct Rect {
    int x = 0, y = 0, w = 0, h = 0;  // GL window coordinates (origin bottom left)
};

// The largest rectangle of aspect `aspect` (w / h) centred in `area`.
Rect letterbox(float aspect, Rect area);
// The window's back buffer in `r` as display values, row 0 at the top.
Image readWindow(Rect r);

// A technique by name with the scene's defaults, the device profile's (with a context) and `values`.
Expected<std::unique_ptr<Technique>> makeTechnique(const Scene& scene, const std::string& name,
                                                   const std::map<std::string, std::string>& values);
// The technique's settings as name -> value text.
std::map<std::string, std::string> currentValues(Technique& t);
// RGBA32F texture holding `image` (re-created when the size changes). Image row 0 is the top.
void uploadImage(gl::Texture& texture, const std::string& label, const Image& image);

class Viewer {
public:
    explicit Viewer(const ViewOptions& options) : o(options) {}
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;
    // Checks the options, opens the window and runs the frame loop; the command's exit code.
    int run();

private:
    // ViewerWindow.cpp: window and input.
    void initWindow();
    void shutdownWindow();
    void pollEvents();
    int pressCount(int key) const;
    void moveSelected(glm::vec3 delta);
    uint32_t currentFrame() const { return static_cast<uint32_t>(std::max(0.0, std::floor(frameF))); }
    bool handleInput(float dt);  // true: F12 (screenshot) was pressed

    // AbComparison.cpp: the A/B state.
    bool showsB() const { return abMode != AbMode::Off; }
    bool readB(Image& out);
    void computeMetrics();
    Expected<void> writeSideImage(Side& side, const std::string& file);
    void rebuildSides();
    glm::ivec2 referenceSize() const { return a.pipeline ? a.pipeline->size() : glm::ivec2(256); }
    std::vector<float> currentView() const;
    void startReference(int spp);
    void followReference();
    void takeReferenceUpdate();
    void techniqueCombo(Side& side, const char* label);
    void abPanel();

    // DebugViewBrowser.cpp: debug views and the display programs.
    Expected<void> buildDisplayPrograms();
    Expected<void> setView(Side& side, const std::string& name);
    void drawSides();
    void debugViewPanel();

    // CameraPaths.cpp: bookmarks, camera path, screenshots.
    Expected<void> takeScreenshot(const std::string& png, const std::string& exr);
    void recordKey();
    Expected<void> savePath(const std::string& file);
    void cameraPanel();
    void screenshotButton(bool screenshotKey);

    // ViewerPanel.cpp: the panel.
    void drawPanel(uint32_t frame, bool screenshotKey);
    void settingsEditor(Side& side);
    void animationPanel(uint32_t frame);
    void frameTimePanel();

    // ViewerActions.cpp: --script.
    Expected<void> runAction(const ScriptAction& act);
    void runScript(bool output);

    const ViewOptions& o;
    // The context is declared first so that every GL object below is released before it.
    std::unique_ptr<gl::Context> context;
    GLFWwindow* window = nullptr;
    std::optional<Scene> scene;
    ViewerSettings viewer;
    render::RenderSettings renderSettings;
    std::optional<glm::ivec2> fixedRenderSize;
    std::vector<ScriptAction> script;

    // A/B (AbComparison.cpp).
    enum class BSource { Technique, Image };
    Side a, b;
    BSource bSource = BSource::Technique;
    AbMode abMode = AbMode::Off;
    Image bImage;  // side B as an image: a stored EXR or the background reference
    std::string bImageName;
    gl::Texture bImageTexture, heatTexture;
    Metrics metrics;
    bool heatmap = false, forceMetrics = false;
    float wipe = 0.5f;
    int component = 0;
    // The view a background reference was started for: camera, frame, lights, animated objects' moves and
    // size, as numbers compared exactly (any change, however small, is another view).
    BackgroundReference background;
    bool referenceActive = false;  // side B is a reference that follows the view
    int referenceSpp = 0, referenceRestarts = 0;
    std::vector<float> referenceView;

    // Debug views (DebugViewBrowser.cpp).
    std::optional<gl::Program> display, displayIds, displayMs, pointsProgram;
    int layer = 0;

    // Camera, bookmarks, path, screenshots (CameraPaths.cpp).
    CameraController controller;
    Camera camera;
    CameraPath path;
    bool followPath = false;
    std::vector<CameraBookmark> bookmarks;
    int shotCounter = 0;

    // Animation and what the arrow keys and ctrl-drag move: light i or object i (animated objects
    // only: static geometry is uploaded once).
    bool playing = true;
    double frameF = 0.0;
    float speed = 1.0f;
    float duration = 0.0f;
    int lastFrame = 1;
    bool selectObject = false;
    int selectedLight = 0, selectedObject = -1;
    std::vector<int> movableObjects;
    float sceneScale = 1.0f;

    // Window, layout, input and the adaptive internal size.
    int fbw = 0, fbh = 0, panelWidth = 0;
    Rect viewArea, sideArea, lastRectA, lastRectB;
    glm::ivec2 renderSize{0};
    float scale = 1.0f;
    int cooldown = 0;
    double lastX = 0, lastY = 0, lastTime = 0.0;

    // Panel.
    std::deque<std::vector<gl::PassTime>> history;
    std::map<std::string, ImU32> passColours;
    std::string status;
    glm::vec4 graphRect{0.0f};  // the frame-time graph as last drawn: x, y, width, height (for `state`)
    size_t graphBars = 0;

    // Script.
    size_t scriptPos = 0;
    int scriptWait = 0;
    bool waitReference = false, quit = false;
    std::string waitFile;  // wait-file: until it exists or waitFileDeadline (glfwGetTime) passes
    double waitFileDeadline = 0.0;
    std::string fatal;  // a script action failed: the viewer ends with this message
    int displayed = 0;
};

}  // namespace bounce
