// `bounce compare TEST REF`: every metric of metrics/ErrorMetrics.h for two images of the same size,
// optionally as JSON and with an error heat map. docs/metrics.md documents the output.
#include "app/Cli.h"
#include "app/Options.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/Heatmap.h"
#include "metrics/LightLeak.h"
#include "reference/PrimaryHits.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace bounce {
namespace {

constexpr const char* kCommand = "compare";
// Heat maps of unbounded per-pixel errors end their colour bar at this percentile, so a few
// fireflies do not push everything else to the bottom colour.
constexpr double kHeatmapTopPercentile = 0.99;

struct CompareArgs {
    std::string testPath, referencePath;
    bool json = false;
    std::string heatmapPath;
    std::string heatmapMetric = "flip";
    float exposureEv = 0.0f;
    std::string toneCurve;  // empty: the default for radiance images (aces)
    double pixelsPerDegree = kFlipDefaultPixelsPerDegree;
    bool exposureGiven = false, toneCurveGiven = false;
    // Light leak (docs/metrics.md): the scene whose declared leak regions are scored, as the images show it.
    std::string leakScene;
    std::vector<std::string> sceneParams;
    uint32_t frame = 0;
    bool sceneParamsGiven = false, frameGiven = false;
};

struct LeakResult {
    double test = 0.0, reference = 0.0;
    size_t darkPixels = 0, litPixels = 0;
};

struct Input {
    std::string path;
    Image image;
    bool radiance = false;  // EXR (linear radiance) rather than PNG (display image)
    ToneMap toneMap;
};

enum class HeatmapMetric { Flip, FlipLdr, FlipHdr, RelMse, Abs };

std::optional<HeatmapMetric> parseHeatmapMetric(const std::string& name) {
    if (name == "flip") return HeatmapMetric::Flip;
    if (name == "flip-ldr") return HeatmapMetric::FlipLdr;
    if (name == "flip-hdr") return HeatmapMetric::FlipHdr;
    if (name == "relmse") return HeatmapMetric::RelMse;
    if (name == "abs") return HeatmapMetric::Abs;
    return std::nullopt;
}

Expected<Input> loadInput(const std::string& path, const ToneMap& radianceToneMap) {
    BOUNCE_TRY(const ImageFormat format, imageFormatFor(path));
    BOUNCE_TRY(Image image, readImage(path));
    if (image.empty()) return makeError("{}: image is empty", path);
    BOUNCE_TRY_VOID(checkFinite(image, path));
    Input in;
    in.path = path;
    in.image = std::move(image);
    in.radiance = format == ImageFormat::Exr;
    in.toneMap = in.radiance ? radianceToneMap : kDisplayImageToneMap;
    return in;
}

const char* kindName(const Input& in) { return in.radiance ? "radiance, EXR" : "display, PNG"; }

nlohmann::json inputJson(const Input& in) {
    return {{"path", in.path},
            {"kind", in.radiance ? "radiance" : "display"},
            {"width", in.image.width()},
            {"height", in.image.height()},
            {"toneMap", {{"curve", toneCurveName(in.toneMap.curve)}, {"exposureEv", in.toneMap.exposureEv}}}};
}

std::string toneMapText(const ToneMap& t) {
    return fmt::format("{} at {:+g} EV", toneCurveName(t.curve), t.exposureEv);
}

// The leak scene's masks at the images' size: each pixel's first surface through the scene's camera
// at the frame (ray cast, as the rasteriser samples pixel centres), inside the dark or the lit box.
Expected<LeakResult> leakScores(const Scene& scene, uint32_t frame, const Input& test, const Input& reference) {
    const LeakRegions& r = *scene.leakRegions;
    const int w = test.image.width(), h = test.image.height();
    BOUNCE_TRY(const PrimaryHits hits, primaryHits(scene, scene.timeOfFrame(frame), w, h));
    PixelMask covered(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) covered.set(x, y, hits.covered[static_cast<size_t>(y) * w + x] != 0);
    const PixelMask dark = boxMask(hits.positions, r.darkMin, r.darkMax, &covered);
    const PixelMask lit = boxMask(hits.positions, r.litMin, r.litMax, &covered);
    LeakResult out{0.0, 0.0, dark.count(), lit.count()};
    if (out.darkPixels == 0 || out.litPixels == 0)
        return makeError("the camera of scene '{}' sees {} pixels of the dark region and {} of the lit one at frame {}, {}x{}: "
                         "both must be in view", scene.name, out.darkPixels, out.litPixels, frame, w, h);
    auto t = lightLeakScore(test.image, dark, lit);
    if (!t) return makeError("test {}: {}", test.path, t.error().message);
    auto ref = lightLeakScore(reference.image, dark, lit);
    if (!ref) return makeError("reference {}: {}", reference.path, ref.error().message);
    out.test = *t;
    out.reference = *ref;
    return out;
}

struct HeatmapResult {
    std::string metricName;
    float low = 0.0f, high = 1.0f;
};

int runCompare(const CompareArgs& args) {
    auto fail = [](const std::string& message) { return failCommand(kCommand, message); };

    // Options first, so a typo costs nothing.
    ToneMap radianceToneMap{args.exposureEv, ToneCurve::Aces};
    if (!args.toneCurve.empty()) {
        auto curve = parseToneCurve(args.toneCurve);
        if (!curve) return fail("--tonemap: " + curve.error().message);
        radianceToneMap.curve = *curve;
    }
    if (!std::isfinite(args.exposureEv)) return fail(fmt::format("--exposure: {} is not a finite number", args.exposureEv));
    if (!(args.pixelsPerDegree > 0.0) || !std::isfinite(args.pixelsPerDegree))
        return fail(fmt::format("--ppd: {} is not a positive number", args.pixelsPerDegree));
    const std::optional<HeatmapMetric> heatmapMetric = parseHeatmapMetric(args.heatmapMetric);
    if (!heatmapMetric)
        return fail(fmt::format("--heatmap-metric: unknown metric '{}' (known: flip, flip-ldr, flip-hdr, relmse, abs)",
                                args.heatmapMetric));
    if (!args.heatmapPath.empty()) {
        auto format = imageFormatFor(args.heatmapPath);
        if (!format) return fail("--heatmap: " + format.error().message);
        if (*format != ImageFormat::Png) return fail(fmt::format("--heatmap: {}: heat maps are written as .png", args.heatmapPath));
        if (auto writable = checkWritable(args.heatmapPath); !writable) return fail("--heatmap: " + writable.error().message);
    }
    std::optional<Scene> leakScene;
    if (args.leakScene.empty()) {
        if (args.sceneParamsGiven) return fail("--scene-param: applies to --leak-scene, which is not given");
        if (args.frameGiven) return fail("--frame: applies to --leak-scene, which is not given");
    } else {
        auto scene = loadSceneWithParams(args.leakScene, args.sceneParams);
        if (!scene) return fail("--leak-scene: " + scene.error().message);
        if (!scene->leakRegions)
            return fail(fmt::format("--leak-scene: scene '{}' declares no leak regions (two-rooms does; a scene file "
                                    "declares them with \"leakRegions\", docs/scene.md)", args.leakScene));
        leakScene = std::move(*scene);
    }

    auto test = loadInput(args.testPath, radianceToneMap);
    if (!test) return fail(test.error().message);
    auto reference = loadInput(args.referencePath, radianceToneMap);
    if (!reference) return fail(reference.error().message);
    if (test->image.width() != reference->image.width() || test->image.height() != reference->image.height())
        return fail(fmt::format("images differ in size: test {} is {}x{}, reference {} is {}x{}", test->path,
                                test->image.width(), test->image.height(), reference->path, reference->image.width(),
                                reference->image.height()));
    if (!test->radiance && !reference->radiance && (args.exposureGiven || args.toneCurveGiven))
        spdlog::warn("compare: --exposure and --tonemap apply to EXR radiance; both inputs are PNG display images");
    if (test->radiance != reference->radiance)
        spdlog::warn("compare: comparing a PNG display image with EXR radiance; the linear metrics (MSE, RMSE, relMSE, "
                     "MAE, HDR-FLIP) treat the PNG's decoded display values as radiance");

    std::optional<LeakResult> leak;
    if (leakScene) {
        // A ratio of radiance: display values (tone-mapped, clamped) would give another number.
        for (const Input* in : {&*test, &*reference})
            if (!in->radiance) return fail(fmt::format("--leak-scene: {} is a display image (PNG); the leak score needs EXR radiance", in->path));
        auto scores = leakScores(*leakScene, args.frame, *test, *reference);
        if (!scores) return fail("--leak-scene: " + scores.error().message);
        leak = *scores;
    }

    CompareOptions options;
    options.testToneMap = test->toneMap;
    options.referenceToneMap = reference->toneMap;
    options.pixelsPerDegree = args.pixelsPerDegree;
    CompareMaps maps;
    auto metrics = compareImages(test->image, reference->image, options, &maps);
    if (!metrics) return fail(metrics.error().message);

    std::optional<HeatmapResult> heatmap;
    if (!args.heatmapPath.empty()) {
        HeatmapMetric which = *heatmapMetric;
        // "flip" follows the inputs: HDR-FLIP for two radiance images, LDR-FLIP when a display image is involved.
        if (which == HeatmapMetric::Flip)
            which = test->radiance && reference->radiance ? HeatmapMetric::FlipHdr : HeatmapMetric::FlipLdr;
        HeatmapResult h;
        ErrorMap map;
        if (which == HeatmapMetric::FlipLdr || which == HeatmapMetric::FlipHdr) {
            const bool hdr = which == HeatmapMetric::FlipHdr;
            h.metricName = hdr ? "flip-hdr" : "flip-ldr";
            map = std::move(hdr ? maps.flipHdr : maps.flipLdr);  // FLIP is in [0, 1] by construction
        } else {
            const bool rel = which == HeatmapMetric::RelMse;
            h.metricName = rel ? "relmse" : "abs";
            map = rel ? relativeSquaredErrorMap(test->image, reference->image)
                      : absoluteErrorMap(test->image, reference->image);
            // Unbounded errors: bar from 0 to the 99th percentile (or the maximum, or 1 for a zero map).
            h.high = map.percentile(kHeatmapTopPercentile);
            if (!(h.high > 0.0f)) h.high = map.maxValue();
            if (!(h.high > 0.0f)) h.high = 1.0f;
        }
        if (auto written = writeHeatmap(args.heatmapPath, map, h.low, h.high); !written)
            return fail(written.error().message);
        heatmap = h;
    }

    const ErrorMetrics& m = *metrics;
    if (args.json) {
        nlohmann::json j;
        j["test"] = inputJson(*test);
        j["reference"] = inputJson(*reference);
        j["pixelsPerDegree"] = args.pixelsPerDegree;
        j["relMseEpsilon"] = kRelMseEpsilon;
        j["metrics"] = toJson(m);
        if (heatmap)
            j["heatmap"] = {{"path", args.heatmapPath}, {"metric", heatmap->metricName}, {"low", heatmap->low}, {"high", heatmap->high}};
        if (leak)
            j["leak"] = {{"scene", args.leakScene}, {"frame", args.frame}, {"test", leak->test}, {"reference", leak->reference},
                         {"darkPixels", leak->darkPixels}, {"litPixels", leak->litPixels}};
        fmt::print("{}\n", j.dump(2));
        return 0;
    }

    fmt::print("test       {} ({}, {}x{}, shown {})\n", test->path, kindName(*test), test->image.width(),
               test->image.height(), toneMapText(test->toneMap));
    fmt::print("reference  {} ({}, {}x{}, shown {})\n", reference->path, kindName(*reference),
               reference->image.width(), reference->image.height(), toneMapText(reference->toneMap));
    fmt::print("MSE        {:<12.6g} linear\n", m.mse);
    fmt::print("RMSE       {:<12.6g} linear\n", m.rmse);
    fmt::print("relMSE     {:<12.6g} linear, (x-r)^2/(r^2+{})\n", m.relMse, kRelMseEpsilon);
    fmt::print("relRMS     {:<12.6g} linear, sqrt(sum (x-r)^2 / sum r^2): read this for dim (indirect-only) images\n",
               m.relRms);
    fmt::print("MAE        {:<12.6g} linear\n", m.mae);
    fmt::print("PSNR       {:<12} displayed, dB, peak 1\n", std::isfinite(m.psnr) ? fmt::format("{:.4f}", m.psnr) : "inf");
    fmt::print("SSIM       {:<12.6f} displayed, mean of R,G,B, 11x11 Gaussian window\n", m.ssim);
    fmt::print("FLIP LDR   {:<12.6f} displayed, mean, {:.2f} ppd\n", m.flipLdr, args.pixelsPerDegree);
    fmt::print("FLIP HDR   {:<12.6f} linear, mean, {:.2f} ppd, {} exposures {:+.2f} .. {:+.2f} EV\n", m.flipHdr,
               args.pixelsPerDegree, m.hdrFlipExposures.count, m.hdrFlipExposures.startEv, m.hdrFlipExposures.stopEv);
    if (leak)
        fmt::print("leak       {:<12.6g} test, dark/lit mean luminance on {}'s leak regions at frame {} ({} and {} pixels); reference {:.6g}\n",
                   leak->test, args.leakScene, args.frame, leak->darkPixels, leak->litPixels, leak->reference);
    if (heatmap)
        fmt::print("heat map   {} ({} per pixel, colour bar {:g} .. {:g})\n", args.heatmapPath, heatmap->metricName,
                   heatmap->low, heatmap->high);
    return 0;
}

}  // namespace

void registerCompareCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Compare a test image with a reference: MSE, RMSE, relMSE, MAE, "
                                                  "PSNR, SSIM, FLIP (LDR and HDR); EXR or PNG, same size");
    cmd->add_option("TEST", args->testPath, "Test image (.exr radiance or .png display image)")->required();
    cmd->add_option("REF", args->referencePath, "Reference image (.exr or .png)")->required();
    cmd->add_flag("--json", args->json, "Print the results as JSON");
    cmd->add_option("--heatmap", args->heatmapPath, "Write a per-pixel error heat map with a colour bar (.png)");
    cmd->add_option("--heatmap-metric", args->heatmapMetric,
                    "Heat map metric: flip (HDR-FLIP for two EXRs, else LDR-FLIP), flip-ldr, flip-hdr, relmse, abs")
        ->capture_default_str();
    CLI::Option* exposure =
        cmd->add_option("--exposure", args->exposureEv, "Exposure in stops applied to EXR inputs before tone mapping")
            ->capture_default_str();
    CLI::Option* tonemap =
        cmd->add_option("--tonemap", args->toneCurve, "Tone curve for EXR inputs: clamp, reinhard, aces (default aces)");
    cmd->add_option("--ppd", args->pixelsPerDegree, "FLIP observer, pixels per degree (default: 0.7 m from a 0.7 m wide 4K screen)")
        ->capture_default_str();
    cmd->add_option("--leak-scene", args->leakScene,
                    "Also score light leaks on this scene's declared leak regions (two-rooms, or a scene file with "
                    "\"leakRegions\"), seen by its camera at the images' size");
    CLI::Option* sceneParam = cmd->add_option("--scene-param", args->sceneParams, "--leak-scene's parameter KEY=VALUE (repeatable)");
    CLI::Option* frame = cmd->add_option("--frame", args->frame, "The frame the images show, for --leak-scene's camera and objects")
                             ->capture_default_str();
    cmd->callback([&action, args, exposure, tonemap, sceneParam, frame] {
        args->exposureGiven = exposure->count() > 0;
        args->toneCurveGiven = tonemap->count() > 0;
        args->sceneParamsGiven = sceneParam->count() > 0;
        args->frameGiven = frame->count() > 0;
        action = [args] { return runCompare(*args); };
    });
}

}  // namespace bounce
