#include "app/CpuJobOptions.h"

#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/Resources.h"

#include <charconv>
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
    // Per pixel: the path tracer's double-precision sums (40 B), their copy kept for a time limit
    // (40 B), the float image (12 B) and its encoded file (up to 12 B), rounded up: an estimate that
    // turns an impossible size into an error instead of an allocation failure or the OOM killer.
    constexpr uint64_t kBytesPerPixel = 128;
    BOUNCE_TRY_VOID(checkMemoryBudget(static_cast<uint64_t>(c.size.x) * static_cast<uint64_t>(c.size.y) * kBytesPerPixel,
                                      fmt::format("--size '{}': the image buffers", a.size)));
    BOUNCE_TRY(c.bounces, parseBounces(a.bounces, unbounded));
    if (!(a.timeLimit >= 0.0) || !std::isfinite(a.timeLimit))
        return makeError("--time-limit: {} is not a number of seconds >= 0", a.timeLimit);
    if (a.threads < 0) return makeError("--threads: {} is negative (0 uses every core)", a.threads);
    if (!std::isfinite(a.exposureEv)) return makeError("--exposure: {} is not a finite number", a.exposureEv);
    auto curve = parseToneCurve(a.toneCurve);
    if (!curve) return makeError("--tonemap: {}", curve.error().message);
    auto format = imageFormatFor(a.out);
    if (!format) return makeError("--out: {}", format.error().message);
    const bool toneMapGiven = (a.exposureOption && a.exposureOption->count() > 0) || (a.toneCurveOption && a.toneCurveOption->count() > 0);
    if (*format == ImageFormat::Exr && toneMapGiven)
        spdlog::warn("{}: --exposure and --tonemap apply to PNG output; {} holds linear radiance", command, a.out);
    if (a.indirectOnly && c.bounces == 0)
        spdlog::warn("{}: --indirect-only with --bounces 0 keeps nothing: the image is black by definition", command);
    c.toneMap = ToneMap{a.exposureEv, *curve};
    return c;
}

}  // namespace bounce
