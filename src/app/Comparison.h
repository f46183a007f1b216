#pragma once
// `bounce compare` as a library: the inputs (EXR radiance, PNG display images, or images held in
// memory by `import bounce`), every metric of metrics/ErrorMetrics.h, a per-pixel heat map, light-leak
// scores on a scene's declared regions, and the reference's noise floor (metrics/NoiseFloor.h) when
// its run record is beside it. The command prints what this returns; `import bounce` returns it.
#include "core/Error.h"
#include "core/Image.h"
#include "core/ToneMap.h"
#include "metrics/ErrorMetrics.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace bounce {

struct CompareInput {
    std::string path;      // or a label for an image held in memory
    Image image;
    bool radiance = true;  // EXR (linear radiance) rather than PNG (display image)
    ToneMap toneMap;
};

// Reads an EXR or PNG (checked: known format, non-empty, finite); EXR inputs are shown with `radianceToneMap`.
Expected<CompareInput> loadCompareInput(const std::string& path, const ToneMap& radianceToneMap);
// An image in memory as radiance (checked non-empty and finite).
Expected<CompareInput> memoryCompareInput(const std::string& label, Image image, const ToneMap& radianceToneMap);

enum class HeatmapMetric { Flip, FlipLdr, FlipHdr, RelMse, Abs };
// "flip", "flip-ldr", "flip-hdr", "relmse", "abs" ("--heatmap-metric: unknown metric ..." otherwise).
Expected<HeatmapMetric> parseHeatmapMetric(const std::string& name);

// The reference's noise: its variance image (when known) and run record, and the floors of every
// metric under the comparison's display transforms.
struct ReferenceNoise {
    std::filesystem::path record;    // empty for a variance given directly
    std::filesystem::path variance;  // empty when only the record's floors were available
    uint32_t samplesPerPixel = 0;
    double meanPixelRelativeStdError = 0.0;
    Image varianceImage;             // empty without a variance image
    nlohmann::json floor;            // noiseFloorJson: from the variance, else the record's (default transforms)
    bool floorFromRecord = false;    // true: the record's floors (compare's default display transforms)
};

// The run record of `bounce reference` beside `referencePath`: STEM.json or record.json in the same
// folder (a study's layout) whose output is that file. nullopt when there is none; an error when one
// is there but unreadable or its variance image is (messages name the file).
Expected<std::optional<ReferenceNoise>> findReferenceNoise(const std::filesystem::path& referencePath);

struct LeakRequest {
    Scene scene;         // with declared leak regions
    std::string name;    // as given (messages)
    uint32_t frame = 0;  // the frame the images show
};

struct LeakResult {
    double test = 0.0, reference = 0.0;
    size_t darkPixels = 0, litPixels = 0;
};

struct Heatmap {
    std::string metricName;  // flip-ldr, flip-hdr, relmse, abs
    ErrorMap map;
    float low = 0.0f, high = 1.0f;  // its colour bar
};

struct Comparison {
    ErrorMetrics metrics;
    std::optional<Heatmap> heatmap;
    std::optional<LeakResult> leak;
    // With the reference's noise: the floor of every metric, which metrics are inside kNoiseFloorFactor
    // of it, and the bias-corrected relMSE (with a variance image).
    std::optional<ReferenceNoise> noise;
    nlohmann::json insideFloor;
    std::optional<double> relMseCorrected;
};

struct CompareRequest {
    double pixelsPerDegree = kFlipDefaultPixelsPerDegree;
    std::optional<HeatmapMetric> heatmap;   // none: no heat map is made
    std::optional<LeakRequest> leak;
    std::optional<ReferenceNoise> noise;    // findReferenceNoise's, or a variance given directly
};

// Both inputs the same size (else "images differ in size: test A is WxH, reference B is WxH").
Expected<Comparison> compareInputs(const CompareInput& test, const CompareInput& reference, const CompareRequest& request);

// The comparison as `bounce compare --json` prints it (without the inputs' fields).
nlohmann::json comparisonJson(const Comparison& c);

}  // namespace bounce
