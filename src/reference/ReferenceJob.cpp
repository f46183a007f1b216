#include "reference/ReferenceJob.h"

#include "reference/LambertKernel.h"

#include "reference/JobOutputs.h"

#include <tbb/task_arena.h>

namespace bounce {

Expected<PathTracerResult> runReferenceJob(const Scene& scene, const ReferenceJob& job,
                                           const ProgressCallback& progress) {
    if (job.output.empty()) {
        if (!job.stats.empty() || !job.variance.empty()) return makeError("a run record or variance image needs an output image");
        BOUNCE_TRY(const PathTracer tracer, PathTracer::create(scene, job.settings));
        return tracer.render(progress);
    }
    BOUNCE_TRY(const ImageFormat format, checkJobOutputs(job.output, job.stats, job.variance));
    BOUNCE_TRY(const PathTracer tracer, PathTracer::create(scene, job.settings));
    PathTracerResult result = tracer.render(progress);
    nlohmann::ordered_json record;
    if (!job.stats.empty()) {
        record = referenceRunRecord(scene, job, result);
        if (job.amendRecord) job.amendRecord(record, result);
    }
    BOUNCE_TRY_VOID(writeJobOutputs(job.output, job.stats, format, result.radiance, job.toneMap, record, job.variance,
                                    &result.variance));
    return result;
}

nlohmann::ordered_json referenceRunRecord(const Scene& scene, const ReferenceJob& job, const PathTracerResult& result) {
    const PathTracerSettings& s = job.settings;
    const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();
    nlohmann::ordered_json record = {
        {"kind", "reference"},
        {"scene", jobSceneRecord(scene, job.scene, job.sceneParams)},
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
        {"output", jobOutputRecord(job.output, job.toneMap)},
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
    };
    // The per-pixel variance image beside the image: what `bounce compare` and studies derive noise floors from.
    // Relative to the record's folder, so the pair can be moved together.
    if (!job.variance.empty())
        record["noise"]["variance"] =
            job.stats.empty() ? job.variance.string()
                              : std::filesystem::absolute(job.variance).lexically_proximate(std::filesystem::absolute(job.stats).parent_path()).string();
    nlohmann::ordered_json renderer = jobLibraryVersions();
    // The vectorised shading kernel's variant on this CPU (docs/reference.md "Performance").
    renderer["shadingKernel"] = lambert::instructionSet();
    record["renderer"] = renderer;
    return record;
}

}  // namespace bounce
