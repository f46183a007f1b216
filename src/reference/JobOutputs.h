#pragma once
// What `bounce reference` and `bounce photon-map` share around their CPU render: checking that the
// image and the run record can be written before any work, writing both atomically after it, and
// the run record's scene, output and library fields.
#include "core/Error.h"
#include "core/Image.h"
#include "core/ImageIo.h"
#include "core/ToneMap.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace bounce {

// Fails (naming the path) when the image's extension is unknown, a file cannot be written, the
// run record is not .json or the variance image not .exr; `stats` and `variance` may be empty (none).
Expected<ImageFormat> checkJobOutputs(const std::filesystem::path& output, const std::filesystem::path& stats,
                                      const std::filesystem::path& variance = {});

// Writes the image (PNG tone-mapped with `toneMap`, EXR linear), when `stats` is set the record, and
// when `variancePath` is set the image `variance` (EXR), all together: a failure leaves none of them.
Expected<void> writeJobOutputs(const std::filesystem::path& output, const std::filesystem::path& stats, ImageFormat format,
                               const Image& radiance, const ToneMap& toneMap, const nlohmann::ordered_json& record,
                               const std::filesystem::path& variancePath = {}, const Image* variance = nullptr);

// {"name", "source", "asked", "params"} of the run record.
nlohmann::ordered_json jobSceneRecord(const Scene& scene, const std::string& asked, const SceneParams& params);
// {"path"} plus {"toneMap"} for PNG outputs.
nlohmann::ordered_json jobOutputRecord(const std::filesystem::path& output, const ToneMap& toneMap);
// The ray-tracing libraries' versions (Embree, TBB) for the record's "renderer" field.
nlohmann::ordered_json jobLibraryVersions();

// The run record's settings that both jobs share, after their own (width, height, spp / photons ...):
// bounces ("unbounded" for kUnbounded), indirectOnly, diffuseOnly, seed, timeLimitSeconds, threads
// (0 resolved to TBB's default concurrency), frame and its time in seconds. `Settings` is
// PathTracerSettings or PhotonMapSettings.
nlohmann::ordered_json jobScopeRecord(const Scene& scene, int bounces, bool unbounded, bool indirectOnly, bool diffuseOnly,
                                      uint64_t seed, double timeLimitSeconds, int threads, uint32_t frame);
template <class Settings>
nlohmann::ordered_json jobScopeRecord(const Scene& scene, const Settings& s) {
    return jobScopeRecord(scene, s.bounces, s.bounces == Settings::kUnbounded, s.indirectOnly, s.diffuseOnly, s.seed,
                          s.timeLimitSeconds, s.threads, s.frame);
}

// The run both jobs share. Without an output the render alone (the caller keeps the result, as
// `import bounce` does; a run record or variance image is then refused with `noOutput`); else the
// outputs checked before any work, render(), the run record makeRecord(result) when `stats` is set,
// and every file written together (a failure leaves none). varianceOf(result): the variance image or
// nullptr.
template <class Result, class Render, class MakeRecord, class VarianceOf>
Expected<Result> runJobWithOutputs(const std::filesystem::path& output, const std::filesystem::path& stats,
                                   const std::filesystem::path& variance, const ToneMap& toneMap, const char* noOutput,
                                   Render render, MakeRecord makeRecord, VarianceOf varianceOf) {
    if (output.empty()) {
        if (!stats.empty() || !variance.empty()) return makeError("{}", noOutput);
        return render();
    }
    BOUNCE_TRY(const ImageFormat format, checkJobOutputs(output, stats, variance));
    BOUNCE_TRY(Result result, render());
    const nlohmann::ordered_json record = stats.empty() ? nlohmann::ordered_json() : makeRecord(result);
    BOUNCE_TRY_VOID(writeJobOutputs(output, stats, format, result.radiance, toneMap, record, variance, varianceOf(result)));
    return result;
}

}  // namespace bounce
