// `bounce compare TEST REF`: every metric of metrics/ErrorMetrics.h for two images of the same size,
// optionally as JSON and with an error heat map. docs/metrics.md documents the output.
#include "app/Cli.h"
#include "app/Comparison.h"
#include "app/Options.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/Heatmap.h"
#include "metrics/NoiseFloor.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace bounce {
namespace {

constexpr const char* kCommand = "compare";

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

const char* kindName(const CompareInput& in) { return in.radiance ? "radiance, EXR" : "display, PNG"; }

nlohmann::json inputJson(const CompareInput& in) {
    return {{"path", in.path},
            {"kind", in.radiance ? "radiance" : "display"},
            {"width", in.image.width()},
            {"height", in.image.height()},
            {"toneMap", {{"curve", toneCurveName(in.toneMap.curve)}, {"exposureEv", in.toneMap.exposureEv}}}};
}

std::string toneMapText(const ToneMap& t) {
    return fmt::format("{} at {:+g} EV", toneCurveName(t.curve), t.exposureEv);
}

// "  0.0123 (inside 2x the floor)" for the printed floor block.
std::string floorText(const nlohmann::json& floor, const nlohmann::json& inside, const char* key, bool psnr = false) {
    const auto f = floor.find(key);
    if (f == floor.end() || !f->is_number()) return "-";
    const auto in = inside.find(key);
    const std::string verdict = in != inside.end() && in->is_boolean() ? (in->get<bool>() ? "  INSIDE 2x the floor" : "") : "";
    return (psnr ? fmt::format("{:.4f}", f->get<double>()) : fmt::format("{:.6g}", f->get<double>())) + verdict;
}

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
    auto heatmapMetric = parseHeatmapMetric(args.heatmapMetric);
    if (!heatmapMetric) return fail(heatmapMetric.error().message);
    CompareRequest request;
    request.pixelsPerDegree = args.pixelsPerDegree;
    if (!args.heatmapPath.empty()) {
        auto format = imageFormatFor(args.heatmapPath);
        if (!format) return fail("--heatmap: " + format.error().message);
        if (*format != ImageFormat::Png) return fail(fmt::format("--heatmap: {}: heat maps are written as .png", args.heatmapPath));
        if (auto writable = checkWritable(args.heatmapPath); !writable) return fail("--heatmap: " + writable.error().message);
        request.heatmap = *heatmapMetric;
    }
    if (args.leakScene.empty()) {
        if (args.sceneParamsGiven) return fail("--scene-param: applies to --leak-scene, which is not given");
        if (args.frameGiven) return fail("--frame: applies to --leak-scene, which is not given");
    } else {
        auto scene = loadSceneWithParams(args.leakScene, args.sceneParams);
        if (!scene) return fail("--leak-scene: " + scene.error().message);
        if (!scene->leakRegions)
            return fail(fmt::format("--leak-scene: scene '{}' declares no leak regions (two-rooms does; a scene file "
                                    "declares them with \"leakRegions\", docs/scene.md)", args.leakScene));
        request.leak = LeakRequest{std::move(*scene), args.leakScene, args.frame};
    }

    auto test = loadCompareInput(args.testPath, radianceToneMap);
    if (!test) return fail(test.error().message);
    auto reference = loadCompareInput(args.referencePath, radianceToneMap);
    if (!reference) return fail(reference.error().message);
    if (test->image.width() == reference->image.width() && test->image.height() == reference->image.height()) {
        if (!test->radiance && !reference->radiance && (args.exposureGiven || args.toneCurveGiven))
            spdlog::warn("compare: --exposure and --tonemap apply to EXR radiance; both inputs are PNG display images");
        if (test->radiance != reference->radiance)
            spdlog::warn("compare: comparing a PNG display image with EXR radiance; the linear metrics (MSE, RMSE, relMSE, "
                         "MAE, HDR-FLIP) treat the PNG's decoded display values as radiance");
    }
    // The reference's noise floor, when `bounce reference --stats` left its record beside it.
    if (reference->radiance) {
        auto noise = findReferenceNoise(args.referencePath);
        if (!noise) return fail(noise.error().message);
        request.noise = std::move(*noise);
    }

    auto comparison = compareInputs(*test, *reference, request);
    if (!comparison) return fail(comparison.error().message);
    const Comparison& c = *comparison;
    if (c.heatmap)
        if (auto written = writeHeatmap(args.heatmapPath, c.heatmap->map, c.heatmap->low, c.heatmap->high); !written)
            return fail(written.error().message);

    const ErrorMetrics& m = c.metrics;
    if (args.json) {
        nlohmann::json j = comparisonJson(c);
        j["test"] = inputJson(*test);
        j["reference"] = inputJson(*reference);
        j["pixelsPerDegree"] = args.pixelsPerDegree;
        if (c.heatmap) j["heatmap"]["path"] = args.heatmapPath;
        if (c.leak) {
            j["leak"]["scene"] = args.leakScene;
            j["leak"]["frame"] = args.frame;
        }
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
    fmt::print("energy     {:<12.6g} test mean / reference mean\n", m.energy);
    if (c.noise) {
        const ReferenceNoise& n = *c.noise;
        fmt::print("noise floor: what an exact image would score against this reference ({} spp, {:.2f}% noise per pixel; "
                   "{}{}); a metric within {}x of its floor cannot be told from the reference's noise\n",
                   n.samplesPerPixel, 100.0 * n.meanPixelRelativeStdError, n.record.string(),
                   n.floorFromRecord ? ", its floors at the default display transforms" : ", variance " + n.variance.string(),
                   kNoiseFloorFactor);
        const nlohmann::json& f = n.floor;
        const nlohmann::json& in = c.insideFloor;
        fmt::print("  relMSE   {}\n", floorText(f, in, "relMse"));
        if (c.relMseCorrected) fmt::print("  relMSE bias-corrected (relMSE minus its floor) {:.6g}\n", *c.relMseCorrected);
        fmt::print("  relRMS   {}\n", floorText(f, in, "relRms"));
        fmt::print("  MAE      {}\n", floorText(f, in, "mae"));
        fmt::print("  PSNR     {}\n", floorText(f, in, "psnr", true));
        fmt::print("  SSIM     {}\n", floorText(f, in, "ssim"));
        fmt::print("  FLIP LDR {}\n", floorText(f, in, "flipLdr"));
        fmt::print("  FLIP HDR {}\n", floorText(f, in, "flipHdr"));
        fmt::print("  energy   {} (standard error of the reference's mean)\n", floorText(f, in, "energy"));
    }
    if (c.leak)
        fmt::print("leak       {:<12.6g} test, dark/lit mean luminance on {}'s leak regions at frame {} ({} and {} pixels); reference {:.6g}\n",
                   c.leak->test, args.leakScene, args.frame, c.leak->darkPixels, c.leak->litPixels, c.leak->reference);
    if (c.heatmap)
        fmt::print("heat map   {} ({} per pixel, colour bar {:g} .. {:g})\n", args.heatmapPath, c.heatmap->metricName,
                   c.heatmap->low, c.heatmap->high);
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
