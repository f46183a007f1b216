#include "reference/ReferenceJob.h"

#include "reference/LambertKernel.h"

#include "reference/JobOutputs.h"


namespace bounce {

Expected<PathTracerResult> runReferenceJob(const Scene& scene, const ReferenceJob& job,
                                           const ProgressCallback& progress) {
    return runJobWithOutputs<PathTracerResult>(
        job.output, job.stats, job.variance, job.toneMap, "a run record or variance image needs an output image",
        [&]() -> Expected<PathTracerResult> {
            BOUNCE_TRY(const PathTracer tracer, PathTracer::create(scene, job.settings));
            return tracer.render(progress);
        },
        [&](const PathTracerResult& result) {
            nlohmann::ordered_json record = referenceRunRecord(scene, job, result);
            if (job.amendRecord) job.amendRecord(record, result);
            return record;
        },
        [](const PathTracerResult& result) { return &result.variance; });
}

nlohmann::ordered_json referenceRunRecord(const Scene& scene, const ReferenceJob& job, const PathTracerResult& result) {
    const PathTracerSettings& s = job.settings;
    nlohmann::ordered_json settings = {{"width", s.width}, {"height", s.height}, {"spp", s.samplesPerPixel}};
    settings.update(jobScopeRecord(scene, s));
    // The diagnostic cone quadrature is no reference: its record says so (its cones, W_k).
    if (!s.firstReflectionCones.empty()) {
        nlohmann::ordered_json cones = nlohmann::ordered_json::array();
        for (const auto& c : s.firstReflectionCones)
            cones.push_back({{"direction", {c.direction.x, c.direction.y, c.direction.z}}, {"halfAngle", c.halfAngle}, {"weight", c.weight}});
        settings["firstReflectionCones"] = cones;
    }
    nlohmann::ordered_json record = {
        {"kind", "reference"},
        {"scene", jobSceneRecord(scene, job.scene, job.sceneParams)},
        {"settings", settings},
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
