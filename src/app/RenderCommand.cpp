// `bounce render`: headless rendering of one technique on one scene, the main path of the lab.
#include "app/Cli.h"
#include "app/Options.h"
#include "app/RenderSession.h"
#include "app/RunRecord.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "gpu/Context.h"
#include "scene/CameraPath.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <chrono>
#include <spdlog/spdlog.h>

#include <optional>

namespace bounce {

namespace {

struct RenderOptions {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string technique = "direct";
    std::string size = "512x512";
    int frames = 1;
    int startFrame = 0;
    std::vector<std::string> settings;
    std::string component = "full";
    std::string out;
    std::string stats;
    int statsEvery = 1;
    std::string cameraPath;
};

// --camera-path: every frame of the path's time range, each written to the --out pattern. A failure
// part way removes the frames already written, so a run leaves all of its frames or none.
int renderCameraPath(const RenderOptions& o, const CameraPath& path, RenderSession& session, Component component) {
    const std::string cmd = "render";
    Scene& scene = session.scene();
    if (auto r = applyLightPoses(scene, path.lights); !r.ok()) return failCommand(cmd, "--camera-path " + o.cameraPath + ": " + r.error().message);
    if (!path.scene.empty() && path.scene != scene.name)
        spdlog::warn("camera path {} was recorded on scene '{}', replayed on '{}'", o.cameraPath, path.scene, scene.name);
    const ToneMap toneMap = session.toneMap();
    std::vector<std::string> written;
    auto fail = [&](const std::string& message) {
        for (const std::string& f : written) std::filesystem::remove(f);
        return failCommand(cmd, message);
    };
    std::vector<FrameStats> frames;
    const auto [first, last] = path.frameRange(scene.frameRate);
    for (uint32_t f = first; f <= last; ++f) {
        const Camera camera = path.evaluate(scene.timeOfFrame(f)).applyTo(scene.camera);
        frames.push_back(session.renderFrame(f, &camera));
        auto image = session.readback(component, fmt::format(" of frame {}", f));
        if (!image.ok()) return fail(image.error().message);
        const std::string file = *formatFramePattern(o.out, f);
        if (auto r = writeImage(file, *image, toneMap); !r.ok()) return fail(r.error().message);
        written.push_back(file);
    }
    if (!o.stats.empty()) {
        nlohmann::json extra = {{"command", "render"}, {"component", o.component}, {"output", o.out},
                                {"camera_path", o.cameraPath}, {"frame_count", frames.size()}, {"start_frame", first}};
        const auto record = session.runRecord(frames, extra);
        if (auto r = writeTextFileAtomic(o.stats, record.dump(2) + "\n"); !r.ok()) return fail(r.error().message);
    }
    spdlog::info("{} on {}: {} camera-path frames ({}..{}) written to {}", o.technique, scene.name, frames.size(), first, last, o.out);
    return 0;
}

int runRender(const RenderOptions& o) {
    const std::string cmd = "render";
    auto size = parseSize(o.size);
    if (!size.ok()) return failCommand(cmd, size.error().message);
    auto component = parseComponent(o.component);
    if (!component.ok()) return failCommand(cmd, "--component: " + component.error().message);
    if (o.frames < 1) return failCommand(cmd, fmt::format("--frames {} must be at least 1", o.frames));
    if (o.startFrame < 0) return failCommand(cmd, fmt::format("--start-frame {} must not be negative", o.startFrame));
    if (o.statsEvery < 1) return failCommand(cmd, fmt::format("--stats-every {} must be at least 1", o.statsEvery));
    // With --camera-path, --out is a pattern: check the first frame's name (same folder and format for all).
    std::string firstOut = o.out;
    if (!o.cameraPath.empty()) {
        if (o.frames != 1 || o.startFrame != 0)
            return failCommand(cmd, "--camera-path sets the frames (its key times); drop --frames and --start-frame");
        auto name = formatFramePattern(o.out, 0);
        if (!name.ok()) return failCommand(cmd, "--out " + name.error().message);
        firstOut = *name;
    }
    if (auto f = imageFormatFor(firstOut); !f.ok()) return failCommand(cmd, "--out " + f.error().message);
    if (auto w = checkWritable(firstOut); !w.ok()) return failCommand(cmd, "--out " + w.error().message);
    if (!o.stats.empty())
        if (auto w = checkWritable(o.stats); !w.ok()) return failCommand(cmd, "--stats " + w.error().message);
    auto technique = createRenderTechnique(o.technique);
    if (!technique.ok()) return failCommand(cmd, technique.error().message);
    const auto loadStart = std::chrono::steady_clock::now();
    auto scene = loadSceneWithParams(o.scene, o.sceneParams);
    // Scene loading (file or generator, and finalizeScene), recorded with --stats (issue 30: load time
    // of Sponza-class scenes).
    const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
    if (!scene.ok()) return failCommand(cmd, scene.error().message);
    std::optional<CameraPath> path;
    if (!o.cameraPath.empty()) {
        auto read = readCameraPath(o.cameraPath);
        if (!read.ok()) return failCommand(cmd, "--camera-path " + read.error().message);
        path = std::move(*read);
    }
    // A run whose timings are recorded (--stats) gets no debug context: synchronous KHR_debug output
    // serialises the driver, and bench/ measures without it (docs/gpu.md "Measured runs"). The session
    // applies the device profile's defaults under the scene's and --set values.
    const auto setupStart = std::chrono::steady_clock::now();
    auto session = RenderSession::create(std::make_shared<Scene>(std::move(*scene)), std::move(*technique), *size, o.settings,
                                         static_cast<uint32_t>(o.startFrame),
                                         o.stats.empty() ? gl::ContextConfig{} : gl::measuredContextConfig());
    // The context, uploading the scene and the technique's set-up (before frame 0).
    const double setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();
    if (!session.ok()) return failCommand(cmd, session.error().message);
    if (path) return renderCameraPath(o, *path, **session, *component);

    std::vector<FrameStats> frames;
    for (int f = o.startFrame; f < o.startFrame + o.frames; ++f) {
        FrameStats stats = (*session)->renderFrame(static_cast<uint32_t>(f));
        // --stats-every N keeps every Nth frame and the last, so a long run's record (and its memory) stays small.
        const int index = f - o.startFrame;
        if (index % o.statsEvery == 0 || index == o.frames - 1) frames.push_back(std::move(stats));
    }
    if (gl::Context::debugErrorCount() > 0)
        spdlog::warn("{} GL errors were reported during rendering", gl::Context::debugErrorCount());
    auto image = (*session)->readback(*component);
    if (!image.ok()) return failCommand(cmd, image.error().message);
    // The image and its run record are written together: a failure leaves neither.
    OutputFiles outputs;
    auto encoded = encodeImage(o.out, *image, (*session)->toneMap());
    if (!encoded.ok()) return failCommand(cmd, encoded.error().message);
    outputs.add(o.out, std::move(*encoded));
    if (!o.stats.empty()) {
        nlohmann::json extra = {{"command", "render"}, {"component", o.component}, {"output", o.out},
                                {"frame_count", o.frames}, {"start_frame", o.startFrame}, {"stats_every", o.statsEvery},
                                {"scene_load_seconds", loadSeconds}, {"setup_seconds", setupSeconds}};
        outputs.add(o.stats, (*session)->runRecord(frames, extra).dump(2) + "\n");
    }
    if (auto r = outputs.commit(); !r.ok()) return failCommand(cmd, r.error().message);
    const auto medians = medianPassTimes(frames);
    spdlog::info("{} on {}: median frame {:.2f} ms GPU, {:.2f} ms CPU", o.technique, (*session)->scene().name,
                 medians.value("frame", 0.0), medians.value("cpu", 0.0));
    if (frames.size() > 1) {
        // A first frame that does the set-up work (radiosity's initial solution) is shown on its own.
        const auto first = firstFrameTimes(frames), rest = medianPassTimesExcludingFirst(frames);
        spdlog::info("first frame {:.2f} ms GPU, {:.2f} ms CPU; median of the {} frames after it {:.2f} ms GPU, {:.2f} ms CPU",
                     first.value("frame", 0.0), first.value("cpu", 0.0), frames.size() - 1, rest.value("frame", 0.0),
                     rest.value("cpu", 0.0));
    }
    return 0;
}

}  // namespace

void registerRenderCommand(CLI::App& root, CommandAction& action) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* c = root.add_subcommand("render", "render a scene with a technique (headless) into an image");
    c->add_option("--scene", options->scene, "built-in scene name or scene/model file")->required();
    c->add_option("--scene-param", options->sceneParams, "built-in scene parameter name=value (repeatable)");
    c->add_option("--technique", options->technique, "technique name (see `bounce list`)")->capture_default_str();
    c->add_option("--size", options->size, "image size WIDTHxHEIGHT")->capture_default_str();
    c->add_option("--frames", options->frames, "frames to render; animation advances, the last is written")
        ->capture_default_str();
    c->add_option("--start-frame", options->startFrame,
                  "first frame (its time is frame / frameRate); a technique that keeps state across frames starts "
                  "its history there")
        ->capture_default_str();
    c->add_option("--set", options->settings, "setting name=value; renderer.NAME for shared passes (repeatable)");
    c->add_option("--component", options->component, "full, direct or indirect")->capture_default_str();
    c->add_option("--out", options->out, "output image (.exr linear radiance, .png tone-mapped)")->required();
    c->add_option("--camera-path", options->cameraPath,
                  "replay a camera path (JSON from `bounce view`) frame by frame; --out is then a pattern such as frame_%04d.png");
    c->add_option("--stats", options->stats, "run record (JSON): settings, GPU, per-pass timings, counters, live GL objects and memory");
    c->add_option("--stats-every", options->statsEvery,
                  "keep every Nth frame (and the last) in the run record: a long run's record stays small")
        ->capture_default_str();
    c->callback([&action, options] { action = [options] { return runRender(*options); }; });
}

}  // namespace bounce
