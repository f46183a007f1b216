#include "app/Comparison.h"

#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "metrics/LightLeak.h"
#include "metrics/NoiseFloor.h"
#include "reference/PrimaryHits.h"

#include <fmt/format.h>

namespace bounce {
namespace {

namespace fs = std::filesystem;

// Heat maps of unbounded per-pixel errors end their colour bar at this percentile, so a few
// fireflies do not push everything else to the bottom colour.
constexpr double kHeatmapTopPercentile = 0.99;

// The leak scene's masks at the images' size: each pixel's first surface through the scene's camera
// at the frame (ray cast, as the rasteriser samples pixel centres), inside the dark or the lit box.
Expected<LeakResult> leakScores(const LeakRequest& leak, const CompareInput& test, const CompareInput& reference) {
    const Scene& scene = leak.scene;
    const LeakRegions& r = *scene.leakRegions;
    const int w = test.image.width(), h = test.image.height();
    BOUNCE_TRY(const PrimaryHits hits, primaryHits(scene, scene.timeOfFrame(leak.frame), w, h));
    PixelMask covered(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) covered.set(x, y, hits.covered[static_cast<size_t>(y) * w + x] != 0);
    const PixelMask dark = boxMask(hits.positions, r.darkMin, r.darkMax, &covered);
    const PixelMask lit = boxMask(hits.positions, r.litMin, r.litMax, &covered);
    LeakResult out{0.0, 0.0, dark.count(), lit.count()};
    if (out.darkPixels == 0 || out.litPixels == 0)
        return makeError("the camera of scene '{}' sees {} pixels of the dark region and {} of the lit one at frame {}, {}x{}: "
                         "both must be in view", scene.name, out.darkPixels, out.litPixels, leak.frame, w, h);
    auto t = lightLeakScore(test.image, dark, lit);
    if (!t) return makeError("test {}: {}", test.path, t.error().message);
    auto ref = lightLeakScore(reference.image, dark, lit);
    if (!ref) return makeError("reference {}: {}", reference.path, ref.error().message);
    out.test = *t;
    out.reference = *ref;
    return out;
}

Expected<nlohmann::json> readJson(const fs::path& path) {
    BOUNCE_TRY(const std::string text, readTextFile(path));
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        return makeError("{}: {}", path.string(), e.what());
    }
}

}  // namespace

Expected<CompareInput> loadCompareInput(const std::string& path, const ToneMap& radianceToneMap) {
    BOUNCE_TRY(const ImageFormat format, imageFormatFor(path));
    BOUNCE_TRY(Image image, readImage(path));
    if (image.empty()) return makeError("{}: image is empty", path);
    BOUNCE_TRY_VOID(checkFinite(image, path));
    CompareInput in;
    in.path = path;
    in.image = std::move(image);
    in.radiance = format == ImageFormat::Exr;
    in.toneMap = in.radiance ? radianceToneMap : kDisplayImageToneMap;
    return in;
}

Expected<CompareInput> memoryCompareInput(const std::string& label, Image image, const ToneMap& radianceToneMap) {
    if (image.empty()) return makeError("{}: image is empty", label);
    BOUNCE_TRY_VOID(checkFinite(image, label));
    CompareInput in;
    in.path = label;
    in.image = std::move(image);
    in.radiance = true;
    in.toneMap = radianceToneMap;
    return in;
}

Expected<HeatmapMetric> parseHeatmapMetric(const std::string& name) {
    if (name == "flip") return HeatmapMetric::Flip;
    if (name == "flip-ldr") return HeatmapMetric::FlipLdr;
    if (name == "flip-hdr") return HeatmapMetric::FlipHdr;
    if (name == "relmse") return HeatmapMetric::RelMse;
    if (name == "abs") return HeatmapMetric::Abs;
    return makeError("--heatmap-metric: unknown metric '{}' (known: flip, flip-ldr, flip-hdr, relmse, abs)", name);
}

Expected<std::optional<ReferenceNoise>> findReferenceNoise(const fs::path& referencePath) {
    const fs::path folder = referencePath.parent_path().empty() ? fs::path(".") : referencePath.parent_path();
    for (const fs::path& candidate : {fs::path(referencePath).replace_extension(".json"), folder / "record.json"}) {
        std::error_code ec;
        if (!fs::is_regular_file(candidate, ec)) continue;
        BOUNCE_TRY(const nlohmann::json record, readJson(candidate));
        // Only a reference's record, and the one of this image (a study's record names "image.exr").
        if (!record.is_object() || record.value("kind", "") != "reference" || !record.contains("noise")) continue;
        const std::string output = record.value("output", nlohmann::json::object()).value("path", "");
        if (fs::path(output).filename() != referencePath.filename()) continue;
        const nlohmann::json& noise = record["noise"];
        ReferenceNoise out;
        out.record = candidate;
        out.samplesPerPixel = record.value("result", nlohmann::json::object()).value("samplesPerPixel", 0u);
        out.meanPixelRelativeStdError = noise.value("meanPixelRelativeStdError", 0.0);
        if (noise.contains("variance") && noise["variance"].is_string()) {
            out.variance = folder / noise["variance"].get<std::string>();
            auto image = readImage(out.variance);
            if (!image) return makeError("{}: its variance image: {}", candidate.string(), image.error().message);
            out.varianceImage = std::move(*image);
        } else if (noise.contains("floor") && noise["floor"].is_object() && !noise["floor"].contains("error")) {
            out.floor = noise["floor"];
            out.floorFromRecord = true;
        } else {
            continue;  // a record from before noise floors: nothing to say
        }
        return std::optional<ReferenceNoise>(std::move(out));
    }
    return std::optional<ReferenceNoise>();
}

Expected<Comparison> compareInputs(const CompareInput& test, const CompareInput& reference, const CompareRequest& request) {
    if (test.image.width() != reference.image.width() || test.image.height() != reference.image.height())
        return makeError("images differ in size: test {} is {}x{}, reference {} is {}x{}", test.path, test.image.width(),
                         test.image.height(), reference.path, reference.image.width(), reference.image.height());
    Comparison out;
    if (request.leak) {
        // A ratio of radiance: display values (tone-mapped, clamped) would give another number.
        for (const CompareInput* in : {&test, &reference})
            if (!in->radiance)
                return makeError("--leak-scene: {} is a display image (PNG); the leak score needs EXR radiance", in->path);
        auto scores = leakScores(*request.leak, test, reference);
        if (!scores) return makeError("--leak-scene: {}", scores.error().message);
        out.leak = *scores;
    }

    CompareOptions options;
    options.testToneMap = test.toneMap;
    options.referenceToneMap = reference.toneMap;
    options.pixelsPerDegree = request.pixelsPerDegree;
    CompareMaps maps;
    BOUNCE_TRY(out.metrics, compareImages(test.image, reference.image, options, &maps));

    if (request.heatmap) {
        HeatmapMetric which = *request.heatmap;
        // "flip" follows the inputs: HDR-FLIP for two radiance images, LDR-FLIP when a display image is involved.
        if (which == HeatmapMetric::Flip) which = test.radiance && reference.radiance ? HeatmapMetric::FlipHdr : HeatmapMetric::FlipLdr;
        Heatmap h;
        if (which == HeatmapMetric::FlipLdr || which == HeatmapMetric::FlipHdr) {
            const bool hdr = which == HeatmapMetric::FlipHdr;
            h.metricName = hdr ? "flip-hdr" : "flip-ldr";
            h.map = std::move(hdr ? maps.flipHdr : maps.flipLdr);  // FLIP is in [0, 1] by construction
        } else {
            const bool rel = which == HeatmapMetric::RelMse;
            h.metricName = rel ? "relmse" : "abs";
            h.map = rel ? relativeSquaredErrorMap(test.image, reference.image) : absoluteErrorMap(test.image, reference.image);
            // Unbounded errors: bar from 0 to the 99th percentile (or the maximum, or 1 for a zero map).
            h.high = h.map.percentile(kHeatmapTopPercentile);
            if (!(h.high > 0.0f)) h.high = h.map.maxValue();
            if (!(h.high > 0.0f)) h.high = 1.0f;
        }
        out.heatmap = std::move(h);
    }

    if (request.noise) {
        ReferenceNoise noise = *request.noise;
        if (!noise.varianceImage.empty()) {
            if (!reference.radiance) return makeError("the reference's variance applies to EXR radiance; {} is a PNG", reference.path);
            auto floor = referenceNoiseFloor(reference.image, noise.varianceImage, options);
            if (!floor) return makeError("variance {}: {}", noise.variance.empty() ? std::string("image") : noise.variance.string(),
                                         floor.error().message);
            noise.floor = noiseFloorJson(*floor);
            noise.floorFromRecord = false;
            out.insideFloor = insideNoiseFloorJson(out.metrics, *floor);
            out.relMseCorrected = biasCorrectedRelMse(test.image, reference.image, noise.varianceImage);
        } else {
            const nlohmann::json measured = toJson(out.metrics);
            out.insideFloor = nlohmann::json::object();
            for (const auto& [metric, value] : noise.floor.items()) {
                const auto m = measured.find(metric);
                out.insideFloor[metric] = value.is_number() && m != measured.end() && m->is_number()
                                              ? nlohmann::json(insideNoiseFloor(metric, m->get<double>(), value.get<double>()))
                                              : nlohmann::json(nullptr);
            }
        }
        out.noise = std::move(noise);
    }
    return out;
}

nlohmann::json comparisonJson(const Comparison& c) {
    nlohmann::json j;
    j["relMseEpsilon"] = kRelMseEpsilon;
    j["metrics"] = toJson(c.metrics);
    if (c.heatmap) j["heatmap"] = {{"metric", c.heatmap->metricName}, {"low", c.heatmap->low}, {"high", c.heatmap->high}};
    if (c.leak)
        j["leak"] = {{"test", c.leak->test}, {"reference", c.leak->reference}, {"darkPixels", c.leak->darkPixels},
                     {"litPixels", c.leak->litPixels}};
    if (c.noise) {
        const ReferenceNoise& n = *c.noise;
        j["noiseFloor"] = {{"record", n.record.empty() ? nlohmann::json(nullptr) : nlohmann::json(n.record.string())},
                           {"variance", n.variance.empty() ? nlohmann::json(nullptr) : nlohmann::json(n.variance.string())},
                           {"samplesPerPixel", n.samplesPerPixel},
                           {"meanPixelRelativeStdError", n.meanPixelRelativeStdError},
                           {"fromRecord", n.floorFromRecord},
                           {"factor", kNoiseFloorFactor},
                           {"floor", n.floor},
                           {"insideFloor", c.insideFloor},
                           {"relMseCorrected", c.relMseCorrected ? nlohmann::json(*c.relMseCorrected) : nlohmann::json(nullptr)}};
    }
    return j;
}

}  // namespace bounce
