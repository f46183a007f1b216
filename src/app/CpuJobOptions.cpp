#include "app/CpuJobOptions.h"

#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/Resources.h"
#include "metrics/NoiseFloor.h"
#include "techniques/vct/ConeQuadrature.h"

#include <algorithm>
#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <cmath>

namespace bounce {

void addCpuJobOptions(CLI::App* cmd, CpuJobArgs& a, const CpuJobHelp& help) {
    cmd->add_option("--scene", a.scene, "Built-in scene name or scene file (.json, .gltf, .glb, .obj, .ply)")->required();
    cmd->add_option("--scene-param", a.sceneParams, "Built-in scene parameter KEY=VALUE (repeatable)");
    cmd->add_option("--size", a.size, "Image size WIDTHxHEIGHT in pixels")->capture_default_str();
    cmd->add_option("--bounces", a.bounces, help.bounces)->capture_default_str();
    cmd->add_flag("--indirect-only", a.indirectOnly, help.indirectOnly);
    cmd->add_flag("--diffuse-only", a.diffuseOnly, help.diffuseOnly);
    cmd->add_option("--time-limit", a.timeLimit, help.timeLimit)->capture_default_str();
    cmd->add_option("--seed", a.seed, "Random seed; the same seed gives the same image on any thread count")->capture_default_str();
    cmd->add_option("--threads", a.threads, "Worker threads (0 = every core)")->capture_default_str();
    cmd->add_option("--frame", a.frame, "Render the scene at time frame / frameRate (as `bounce render` frame F)")->capture_default_str();
    cmd->add_option("--out", a.out, "Output image: .exr (linear radiance) or .png (tone-mapped)")->required();
    cmd->add_option("--stats", a.stats, "Write the run record (JSON) here");
    a.exposureOption = cmd->add_option("--exposure", a.exposureEv, "PNG only: exposure in stops before the tone curve")->capture_default_str();
    a.toneCurveOption = cmd->add_option("--tonemap", a.toneCurve, "PNG only: tone curve aces, reinhard or clamp")->capture_default_str();
    cmd->add_flag("--progress", a.progress, "Draw the progress bar even when stderr is not a terminal");
}

namespace {

Expected<int> parseBounces(const std::string& text, int unbounded) {
    if (text == "unbounded" || text == "inf" || text == "-1") return unbounded;
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return makeError("--bounces: '{}' is not an integer", text);
    if (value < 0) return makeError("--bounces: {} is negative (use 'unbounded' for no limit)", value);
    return value;
}

}  // namespace

Expected<CpuJobCommon> checkCpuJobArgs(const CpuJobArgs& a, const char* command, int unbounded) {
    CpuJobCommon c;
    BOUNCE_TRY(c.sceneParams, parseAssignments(a.sceneParams, "--scene-param"));
    if (c.sceneParams.size() != a.sceneParams.size()) return makeError("--scene-param: a key is given twice");
    BOUNCE_TRY(c.size, parseSize(a.size));
    // Per pixel: the path tracer's double-precision sums (64 B), their copy kept for a time limit
    // (64 B), the float image and the variance image (12 B each) and their encoded files (up to 12 B
    // each), rounded up: an estimate that turns an impossible size into an error instead of an
    // allocation failure or the OOM killer.
    constexpr uint64_t kBytesPerPixel = 192;
    BOUNCE_TRY_VOID(checkMemoryBudget(static_cast<uint64_t>(c.size.x) * static_cast<uint64_t>(c.size.y) * kBytesPerPixel,
                                      fmt::format("--size '{}': the image buffers", a.size)));
    BOUNCE_TRY(c.bounces, parseBounces(a.bounces, unbounded));
    if (!(a.timeLimit >= 0.0) || !std::isfinite(a.timeLimit))
        return makeError("--time-limit: {} is not a number of seconds >= 0", a.timeLimit);
    if (a.threads < 0) return makeError("--threads: {} is negative (0 uses every core)", a.threads);
    if (!std::isfinite(a.exposureEv)) return makeError("--exposure: {} is not a finite number", a.exposureEv);
    auto curve = parseToneCurve(a.toneCurve);
    if (!curve) return makeError("--tonemap: {}", curve.error().message);
    if (!a.out.empty()) {
        auto format = imageFormatFor(a.out);
        if (!format) return makeError("--out: {}", format.error().message);
        const bool toneMapGiven = (a.exposureOption && a.exposureOption->count() > 0) || (a.toneCurveOption && a.toneCurveOption->count() > 0);
        if (*format == ImageFormat::Exr && toneMapGiven)
            spdlog::warn("{}: --exposure and --tonemap apply to PNG output; {} holds linear radiance", command, a.out);
    }
    if (a.indirectOnly && c.bounces == 0)
        spdlog::warn("{}: --indirect-only with --bounces 0 keeps nothing: the image is black by definition", command);
    c.toneMap = ToneMap{a.exposureEv, *curve};
    return c;
}

Expected<ReferenceJob> referenceJobFromArgs(const ReferenceArgs& args) {
    BOUNCE_TRY(const CpuJobCommon common, checkCpuJobArgs(args, "reference", PathTracerSettings::kUnbounded));
    if (args.spp == 0) return makeError("--spp: 0: at least one sample per pixel is needed");
    if (!args.variance.empty() && args.stats.empty())
        return makeError("--variance: needs --stats (the run record names the variance image for `bounce compare`)");
    ReferenceJob job;
    job.scene = args.scene;
    job.sceneParams = common.sceneParams;
    job.settings.width = common.size.x;
    job.settings.height = common.size.y;
    job.settings.samplesPerPixel = args.spp;
    job.settings.bounces = common.bounces;
    job.settings.indirectOnly = args.indirectOnly;
    job.settings.diffuseOnly = args.diffuseOnly;
    job.settings.seed = args.seed;
    job.settings.timeLimitSeconds = args.timeLimit;
    job.settings.threads = args.threads;
    job.settings.frame = args.frame;
    if (args.firstReflection == "vct-cones") {
        job.settings.firstReflectionCones = vct::diffuseQuadratureCones();
    } else if (args.firstReflection != "cosine") {
        return makeError("--first-reflection: '{}' is not cosine or vct-cones", args.firstReflection);
    }
    job.output = args.out;
    job.stats = args.stats;
    job.variance = args.variance;
    job.toneMap = common.toneMap;
    job.amendRecord = addNoiseFloor;
    return job;
}

Expected<PhotonMapJob> photonMapJobFromArgs(const PhotonMapArgs& args) {
    BOUNCE_TRY(const CpuJobCommon common, checkCpuJobArgs(args, "photon-map", PhotonMapSettings::kUnbounded));
    if (args.photons == 0) return makeError("--photons: 0: at least one photon is needed");
    if (args.k < 2) return makeError("--k: {}: the estimate needs at least 2 nearest photons", args.k);
    if (!(args.maxRadius >= 0.0f) || !std::isfinite(args.maxRadius))
        return makeError("--max-radius: {} is not a number of metres >= 0", args.maxRadius);
    if (args.spp == 0) return makeError("--spp: 0: at least one camera ray per pixel is needed");
    PhotonMapJob job;
    job.scene = args.scene;
    job.sceneParams = common.sceneParams;
    PhotonMapSettings& s = job.settings;
    s.width = common.size.x;
    s.height = common.size.y;
    s.photons = args.photons;
    s.k = args.k;
    s.maxRadius = args.maxRadius;
    s.samplesPerPixel = args.spp;
    s.bounces = common.bounces;
    s.indirectOnly = args.indirectOnly;
    s.diffuseOnly = args.diffuseOnly;
    s.seed = args.seed;
    s.timeLimitSeconds = args.timeLimit;
    s.threads = args.threads;
    s.frame = args.frame;
    job.output = args.out;
    job.stats = args.stats;
    job.toneMap = common.toneMap;
    return job;
}

void addNoiseFloor(nlohmann::ordered_json& record, const PathTracerResult& result) {
    auto floor = referenceNoiseFloor(result.radiance, result.variance);
    record["noise"]["floor"] = floor ? nlohmann::ordered_json(noiseFloorJson(*floor))
                                     : nlohmann::ordered_json({{"error", floor.error().message}});
}

void ProgressLine::draw(const char* label, double fraction, const char* detailFormat, ...) {
    if (!m_enabled) return;
    // Width of the bar in characters.
    constexpr int kBarWidth = 30;
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", label, std::string(static_cast<size_t>(filled), '#').c_str(),
                 std::string(static_cast<size_t>(kBarWidth - filled), '-').c_str(), static_cast<int>(100.0 * fraction));
    va_list detail;
    va_start(detail, detailFormat);
    std::vfprintf(stderr, detailFormat, detail);
    va_end(detail);
    std::fflush(stderr);
    m_drawn = true;
}

void ProgressLine::finish() {
    if (m_drawn) std::fputc('\n', stderr);
    m_drawn = false;
}

}  // namespace bounce
