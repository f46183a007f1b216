// `bounce reference`: the ground-truth image of a scene, from the CPU path tracer (Embree + TBB).
// docs/reference.md documents the light-transport scopes, the run record and the noise estimate.
#include "app/Cli.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/ToneMap.h"
#include "reference/ReferenceJob.h"
#include "scene/SceneLoader.h"

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace bounce {
namespace {

constexpr const char* kCommand = "reference";
// Image sides above this are surely a typo (and would need gigabytes of accumulators).
constexpr int kMaxImageSide = 16384;
// Width of the progress bar in characters.
constexpr int kBarWidth = 30;

struct ReferenceArgs {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string size = "512x512";
    uint32_t spp = 256;
    std::string bounces = "unbounded";
    bool indirectOnly = false;
    bool diffuseOnly = false;
    double timeLimit = 0.0;
    uint64_t seed = 0;
    int threads = 0;
    uint32_t frame = 0;
    std::string out;
    std::string stats;
    float exposureEv = 0.0f;
    std::string toneCurve = "aces";
    bool progress = false;
    bool toneMapGiven = false;
};

Expected<int> parseInt(const std::string& text, const std::string& what) {
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        return makeError("{}: '{}' is not an integer", what, text);
    return value;
}

Expected<std::pair<int, int>> parseSize(const std::string& text) {
    const size_t x = text.find('x');
    if (x == std::string::npos) return makeError("--size: '{}' is not WIDTHxHEIGHT (e.g. 512x512)", text);
    BOUNCE_TRY(const int width, parseInt(text.substr(0, x), "--size width"));
    BOUNCE_TRY(const int height, parseInt(text.substr(x + 1), "--size height"));
    if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
        return makeError("--size: {}x{}: each side must be between 1 and {}", width, height, kMaxImageSide);
    return std::pair{width, height};
}

Expected<int> parseBounces(const std::string& text) {
    if (text == "unbounded" || text == "inf" || text == "-1") return PathTracerSettings::kUnbounded;
    BOUNCE_TRY(const int bounces, parseInt(text, "--bounces"));
    if (bounces < 0) return makeError("--bounces: {} is negative (use 'unbounded' for no limit)", bounces);
    return bounces;
}

Expected<SceneParams> parseSceneParams(const std::vector<std::string>& items) {
    SceneParams params;
    for (const std::string& item : items) {
        const size_t eq = item.find('=');
        if (eq == std::string::npos || eq == 0) return makeError("--scene-param: '{}' is not KEY=VALUE", item);
        const std::string key = item.substr(0, eq);
        if (params.count(key)) return makeError("--scene-param: '{}' is given twice", key);
        params[key] = item.substr(eq + 1);
    }
    return params;
}

// One line on stderr, redrawn after every pass.
class ProgressBar {
public:
    explicit ProgressBar(bool enabled) : m_enabled(enabled) {}
    ~ProgressBar() { finish(); }

    void update(const RenderProgress& p, double timeLimit) {
        if (!m_enabled) return;
        const double fraction = static_cast<double>(p.samplesDone) / std::max(1u, p.samplesTarget);
        double eta = fraction > 0.0 ? p.elapsedSeconds * (1.0 - fraction) / fraction : 0.0;
        if (timeLimit > 0.0) eta = std::min(eta, std::max(0.0, timeLimit - p.elapsedSeconds));
        const int filled = static_cast<int>(fraction * kBarWidth);
        std::fprintf(stderr, "\rreference [%s%s] %3d%%  %u/%u spp  %.1f s  ETA %.0f s   ",
                     std::string(static_cast<size_t>(filled), '#').c_str(),
                     std::string(static_cast<size_t>(kBarWidth - filled), '-').c_str(),
                     static_cast<int>(100.0 * fraction), p.samplesDone, p.samplesTarget, p.elapsedSeconds, eta);
        std::fflush(stderr);
        m_drawn = true;
    }

    void finish() {
        if (m_drawn) std::fputc('\n', stderr);
        m_drawn = false;
    }

private:
    bool m_enabled;
    bool m_drawn = false;
};

int runReference(const ReferenceArgs& args) {
    const auto fail = [](const std::string& message) { return failCommand(kCommand, message); };

    // Every flag is checked before the scene is loaded, so a typo costs nothing.
    ReferenceJob job;
    job.scene = args.scene;
    auto params = parseSceneParams(args.sceneParams);
    if (!params) return fail(params.error().message);
    job.sceneParams = *params;
    auto size = parseSize(args.size);
    if (!size) return fail(size.error().message);
    auto bounces = parseBounces(args.bounces);
    if (!bounces) return fail(bounces.error().message);
    if (args.spp == 0) return fail("--spp: 0: at least one sample per pixel is needed");
    if (!(args.timeLimit >= 0.0) || !std::isfinite(args.timeLimit))
        return fail(fmt::format("--time-limit: {} is not a number of seconds >= 0", args.timeLimit));
    if (args.threads < 0) return fail(fmt::format("--threads: {} is negative (0 uses every core)", args.threads));
    if (!std::isfinite(args.exposureEv)) return fail(fmt::format("--exposure: {} is not a finite number", args.exposureEv));
    auto curve = parseToneCurve(args.toneCurve);
    if (!curve) return fail("--tonemap: " + curve.error().message);
    auto format = imageFormatFor(args.out);
    if (!format) return fail("--out: " + format.error().message);
    if (*format == ImageFormat::Exr && args.toneMapGiven)
        spdlog::warn("reference: --exposure and --tonemap apply to PNG output; {} holds linear radiance", args.out);

    job.settings.width = size->first;
    job.settings.height = size->second;
    job.settings.samplesPerPixel = args.spp;
    job.settings.bounces = *bounces;
    job.settings.indirectOnly = args.indirectOnly;
    job.settings.diffuseOnly = args.diffuseOnly;
    job.settings.seed = args.seed;
    job.settings.timeLimitSeconds = args.timeLimit;
    job.settings.threads = args.threads;
    job.settings.frame = args.frame;
    job.output = args.out;
    job.stats = args.stats;
    job.toneMap = ToneMap{args.exposureEv, *curve};

    if (args.indirectOnly && *bounces == 0)
        spdlog::warn("reference: --indirect-only with --bounces 0 keeps nothing: the image is black by definition");

    auto scene = loadScene(args.scene, job.sceneParams);
    if (!scene) return fail(scene.error().message);

    ProgressBar bar(args.progress || ::isatty(STDERR_FILENO) != 0);
    auto result = runReferenceJob(*scene, job, [&](const RenderProgress& p) { bar.update(p, args.timeLimit); });
    bar.finish();
    if (!result) return fail(result.error().message);

    const PathTracerResult& r = *result;
    spdlog::info("reference: {} {}x{}, {} spp{} in {:.1f} s ({:.2f} M paths/s, {:.1f} M rays/s); noise {:.2f}% per "
                 "pixel, {:.3f}% image mean; wrote {}{}",
                 scene->name, job.settings.width, job.settings.height, r.samplesPerPixel,
                 r.stoppedByTimeLimit ? fmt::format(" (time limit; {} asked)", args.spp) : std::string(),
                 r.renderSeconds, r.pathsPerSecond() * 1e-6, r.raysPerSecond() * 1e-6,
                 100.0 * r.noise.meanPixelRelativeError, 100.0 * r.noise.imageRelativeError, args.out,
                 args.stats.empty() ? std::string() : " and " + args.stats);
    return 0;
}

}  // namespace

void registerReferenceCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<ReferenceArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Render the ground truth of a scene with the CPU path tracer "
                                                  "(Embree, TBB): EXR radiance or tone-mapped PNG, plus a run record");
    cmd->add_option("--scene", args->scene, "Built-in scene name or scene file (.json, .gltf, .glb, .obj, .ply)")
        ->required();
    cmd->add_option("--scene-param", args->sceneParams, "Built-in scene parameter KEY=VALUE (repeatable)");
    cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT in pixels")->capture_default_str();
    cmd->add_option("--spp", args->spp, "Samples (camera paths) per pixel")->capture_default_str();
    cmd->add_option("--bounces", args->bounces,
                    "Indirect bounces K (paths reflect at most K+1 times; 0 = direct light only), or 'unbounded'")
        ->capture_default_str();
    cmd->add_flag("--indirect-only", args->indirectOnly,
                  "Keep only light that reflected at least twice (full minus emitted and direct)");
    cmd->add_flag("--diffuse-only", args->diffuseOnly, "Use only the Lambert lobe after the first reflection");
    cmd->add_option("--time-limit", args->timeLimit,
                    "Stop after the last pass that fits in SEC seconds (0 = no limit); the record keeps the spp reached")
        ->capture_default_str();
    cmd->add_option("--seed", args->seed, "Random seed; the same seed gives the same image on any thread count")
        ->capture_default_str();
    cmd->add_option("--threads", args->threads, "Worker threads (0 = every core)")->capture_default_str();
    cmd->add_option("--frame", args->frame, "Render the scene at time frame / frameRate (as `bounce render` frame F)")
        ->capture_default_str();
    cmd->add_option("--out", args->out, "Output image: .exr (linear radiance) or .png (tone-mapped)")->required();
    cmd->add_option("--stats", args->stats, "Write the run record (JSON) here");
    CLI::Option* exposure =
        cmd->add_option("--exposure", args->exposureEv, "PNG only: exposure in stops before the tone curve")
            ->capture_default_str();
    CLI::Option* tonemap =
        cmd->add_option("--tonemap", args->toneCurve, "PNG only: tone curve aces, reinhard or clamp")->capture_default_str();
    cmd->add_flag("--progress", args->progress, "Draw the progress bar even when stderr is not a terminal");
    cmd->callback([&action, args, exposure, tonemap] {
        args->toneMapGiven = exposure->count() > 0 || tonemap->count() > 0;
        action = [args] { return runReference(*args); };
    });
}

}  // namespace bounce
