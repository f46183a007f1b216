// `bounce photon-map`: the photon-mapping ground truth of a scene (src/reference/PhotonMap.h), run
// like `bounce reference`: flags checked before any work, progress on stderr, a time limit, a run
// record, one-line errors and no half-written output. docs/techniques/photon-map.md documents it.
#include "app/Cli.h"
#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/ToneMap.h"
#include "reference/PhotonMapJob.h"
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

constexpr const char* kCommand = "photon-map";
constexpr int kBarWidth = 30;

struct PhotonMapArgs {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string size = "512x512";
    uint64_t photons = 1'000'000;
    int k = 100;
    float maxRadius = 0.0f;
    uint32_t spp = 4;
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

Expected<int> parseBounces(const std::string& text) {
    if (text == "unbounded" || text == "inf" || text == "-1") return PhotonMapSettings::kUnbounded;
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return makeError("--bounces: '{}' is not an integer", text);
    if (value < 0) return makeError("--bounces: {} is negative (use 'unbounded' for no limit)", value);
    return value;
}

class ProgressBar {
public:
    explicit ProgressBar(bool enabled) : m_enabled(enabled) {}
    ~ProgressBar() { finish(); }

    void update(const PhotonMapProgress& p) {
        if (!m_enabled) return;
        const double fraction = static_cast<double>(p.done) / static_cast<double>(std::max<uint64_t>(1, p.target));
        const int filled = static_cast<int>(fraction * kBarWidth);
        const bool tracing = p.phase == PhotonMapProgress::Phase::Tracing;
        std::fprintf(stderr, "\rphoton-map %s [%s%s] %3d%%  %llu/%llu %s  %.1f s   ", tracing ? "tracing" : "gathered",
                     std::string(static_cast<size_t>(filled), '#').c_str(),
                     std::string(static_cast<size_t>(kBarWidth - filled), '-').c_str(), static_cast<int>(100.0 * fraction),
                     static_cast<unsigned long long>(p.done), static_cast<unsigned long long>(p.target),
                     tracing ? "photons" : "rows", p.elapsedSeconds);
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

int runPhotonMap(const PhotonMapArgs& args) {
    const auto fail = [](const std::string& message) { return failCommand(kCommand, message); };
    PhotonMapJob job;
    job.scene = args.scene;
    auto params = parseAssignments(args.sceneParams, "--scene-param");
    if (!params) return fail(params.error().message);
    job.sceneParams = *params;
    auto size = parseSize(args.size);
    if (!size) return fail(size.error().message);
    auto bounces = parseBounces(args.bounces);
    if (!bounces) return fail(bounces.error().message);
    if (args.photons == 0) return fail("--photons: 0: at least one photon is needed");
    if (args.k < 2) return fail(fmt::format("--k: {}: the estimate needs at least 2 nearest photons", args.k));
    if (!(args.maxRadius >= 0.0f) || !std::isfinite(args.maxRadius))
        return fail(fmt::format("--max-radius: {} is not a number of metres >= 0", args.maxRadius));
    if (args.spp == 0) return fail("--spp: 0: at least one camera ray per pixel is needed");
    if (!(args.timeLimit >= 0.0) || !std::isfinite(args.timeLimit))
        return fail(fmt::format("--time-limit: {} is not a number of seconds >= 0", args.timeLimit));
    if (args.threads < 0) return fail(fmt::format("--threads: {} is negative (0 uses every core)", args.threads));
    if (!std::isfinite(args.exposureEv)) return fail(fmt::format("--exposure: {} is not a finite number", args.exposureEv));
    auto curve = parseToneCurve(args.toneCurve);
    if (!curve) return fail("--tonemap: " + curve.error().message);
    auto format = imageFormatFor(args.out);
    if (!format) return fail("--out: " + format.error().message);
    if (*format == ImageFormat::Exr && args.toneMapGiven)
        spdlog::warn("photon-map: --exposure and --tonemap apply to PNG output; {} holds linear radiance", args.out);

    PhotonMapSettings& s = job.settings;
    s.width = size->x;
    s.height = size->y;
    s.photons = args.photons;
    s.k = args.k;
    s.maxRadius = args.maxRadius;
    s.samplesPerPixel = args.spp;
    s.bounces = *bounces;
    s.indirectOnly = args.indirectOnly;
    s.diffuseOnly = args.diffuseOnly;
    s.seed = args.seed;
    s.timeLimitSeconds = args.timeLimit;
    s.threads = args.threads;
    s.frame = args.frame;
    job.output = args.out;
    job.stats = args.stats;
    job.toneMap = ToneMap{args.exposureEv, *curve};
    if (args.indirectOnly && *bounces == 0)
        spdlog::warn("photon-map: --indirect-only with --bounces 0 keeps nothing: the image is black by definition");

    auto scene = loadScene(args.scene, job.sceneParams);
    if (!scene) return fail(scene.error().message);

    ProgressBar bar(args.progress || ::isatty(STDERR_FILENO) != 0);
    auto result = runPhotonMapJob(*scene, job, [&](const PhotonMapProgress& p) { bar.update(p); });
    bar.finish();
    if (!result) return fail(result.error().message);
    const PhotonMapResult& r = *result;
    spdlog::info("photon-map: {} {}x{}, {} photons emitted{}, {} stored ({:.1f} MB), k {}: trace {:.1f} s, tree {:.2f} s, "
                 "gather {:.1f} s; mean radius {:.4f} m; wrote {}{}",
                 scene->name, s.width, s.height, r.photonsEmitted,
                 r.stoppedByTimeLimit ? fmt::format(" (time limit; {} asked)", args.photons) : std::string(),
                 r.photonsStored, static_cast<double>(r.mapBytes) * 1e-6, s.k, r.traceSeconds, r.treeSeconds,
                 r.gatherSeconds, r.meanGatherRadius, args.out, args.stats.empty() ? std::string() : " and " + args.stats);
    return 0;
}

}  // namespace

void registerPhotonMapCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<PhotonMapArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Render a scene by CPU photon mapping (Embree, nanoflann kd-tree, "
                                                  "k-nearest radiance estimate): the ground truth of photon splatting");
    cmd->add_option("--scene", args->scene, "Built-in scene name or scene file (.json, .gltf, .glb, .obj, .ply)")
        ->required();
    cmd->add_option("--scene-param", args->sceneParams, "Built-in scene parameter KEY=VALUE (repeatable)");
    cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT in pixels")->capture_default_str();
    cmd->add_option("--photons", args->photons, "Photons emitted from the lights")->capture_default_str();
    cmd->add_option("--k", args->k, "Nearest photons per estimate (k-1 summed inside the k-th's radius)")
        ->capture_default_str();
    cmd->add_option("--max-radius", args->maxRadius, "Cap on the gather radius in metres (0 = none)")->capture_default_str();
    cmd->add_option("--spp", args->spp, "Jittered camera rays (gathers) per pixel")->capture_default_str();
    cmd->add_option("--bounces", args->bounces,
                    "Indirect bounces K as `bounce reference`: photons are stored after at most K reflections")
        ->capture_default_str();
    cmd->add_flag("--indirect-only", args->indirectOnly,
                  "Store photons only after their first reflection: the light of `bounce reference --indirect-only`");
    cmd->add_flag("--diffuse-only", args->diffuseOnly, "Photons bounce by the Lambert lobe alone");
    cmd->add_option("--time-limit", args->timeLimit,
                    "Stop tracing photons after the last pass that started within SEC seconds (0 = no limit)")
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
        action = [args] { return runPhotonMap(*args); };
    });
}

}  // namespace bounce
