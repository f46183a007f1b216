#include "reference/ReferenceJob.h"

#include "reference/LambertKernel.h"

#include "core/FileIo.h"
#include "core/ImageIo.h"

#include <embree3/rtcore_config.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>

namespace bounce {

Expected<PathTracerResult> runReferenceJob(const Scene& scene, const ReferenceJob& job,
                                           const ProgressCallback& progress) {
    BOUNCE_TRY(const ImageFormat format, imageFormatFor(job.output));
    BOUNCE_TRY_VOID(checkWritable(job.output));
    if (!job.stats.empty()) {
        if (job.stats.extension() != ".json")
            return makeError("{}: the run record is JSON: use a .json file name", job.stats.string());
        BOUNCE_TRY_VOID(checkWritable(job.stats));
    }
    BOUNCE_TRY(const PathTracer tracer, PathTracer::create(scene, job.settings));
    PathTracerResult result = tracer.render(progress);
    const ToneMap toneMap = format == ImageFormat::Png ? job.toneMap : ToneMap{};
    BOUNCE_TRY_VOID(writeImage(job.output, result.radiance, toneMap));
    if (!job.stats.empty())
        BOUNCE_TRY_VOID(writeTextFileAtomic(job.stats, referenceRunRecord(scene, job, result).dump(2) + "\n"));
    return result;
}

nlohmann::ordered_json referenceRunRecord(const Scene& scene, const ReferenceJob& job, const PathTracerResult& result) {
    const PathTracerSettings& s = job.settings;
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (const auto& [key, value] : job.sceneParams) params[key] = value;
    nlohmann::ordered_json output = {{"path", job.output.string()}};
    if (auto format = imageFormatFor(job.output); format && *format == ImageFormat::Png)
        output["toneMap"] = {{"curve", toneCurveName(job.toneMap.curve)}, {"exposureEv", job.toneMap.exposureEv}};
    const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();
    return {
        {"kind", "reference"},
        {"scene", {{"name", scene.name}, {"source", scene.source}, {"asked", job.scene}, {"params", params}}},
        {"settings",
         {{"width", s.width},
          {"height", s.height},
          {"spp", s.samplesPerPixel},
          {"bounces", s.bounces == PathTracerSettings::kUnbounded ? nlohmann::ordered_json("unbounded") : nlohmann::ordered_json(s.bounces)},
          {"indirectOnly", s.indirectOnly},
          {"diffuseOnly", s.diffuseOnly},
          {"seed", s.seed},
          {"timeLimitSeconds", s.timeLimitSeconds},
          {"threads", threads},
          {"frame", s.frame},
          {"timeSeconds", scene.timeOfFrame(s.frame)}}},
        {"output", output},
        {"result",
         {{"samplesPerPixel", result.samplesPerPixel},
          {"stoppedByTimeLimit", result.stoppedByTimeLimit},
          {"buildSeconds", result.buildSeconds},
          {"renderSeconds", result.renderSeconds},
          {"paths", result.paths},
          {"rays", result.rays},
          {"shadowRays", result.shadowRays},
          {"pathsPerSecond", result.pathsPerSecond()},
          {"raysPerSecond", result.raysPerSecond()},
          {"invalidSamples", result.invalidSamples}}},
        {"noise",
         {{"meanPixelRelativeStdError", result.noise.meanPixelRelativeError},
          {"imageRelativeStdError", result.noise.imageRelativeError},
          {"pixelsMeasured", result.noise.pixelsMeasured}}},
        {"renderer",
         {{"embree", fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH)},
          {"tbb", TBB_VERSION_STRING},
          // The vectorised shading kernel's variant on this CPU (docs/reference.md "Performance").
          {"shadingKernel", lambert::instructionSet()}}},
    };
}

}  // namespace bounce
