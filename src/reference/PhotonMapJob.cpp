#include "reference/PhotonMapJob.h"

#include "reference/JobOutputs.h"

#include <nanoflann.hpp>
#include <tbb/task_arena.h>

namespace bounce {

Expected<PhotonMapResult> runPhotonMapJob(const Scene& scene, const PhotonMapJob& job,
                                          const PhotonMapProgressCallback& progress) {
    if (job.output.empty()) {  // nothing written: the caller keeps the result (`import bounce`)
        if (!job.stats.empty()) return makeError("a run record needs an output image");
        BOUNCE_TRY(const PhotonMapper mapper, PhotonMapper::create(scene, job.settings));
        return mapper.render(progress);
    }
    BOUNCE_TRY(const ImageFormat format, checkJobOutputs(job.output, job.stats));
    BOUNCE_TRY(const PhotonMapper mapper, PhotonMapper::create(scene, job.settings));
    PhotonMapResult result = mapper.render(progress);
    BOUNCE_TRY_VOID(writeJobOutputs(job.output, job.stats, format, result.radiance, job.toneMap,
                                    job.stats.empty() ? nlohmann::ordered_json() : photonMapRunRecord(scene, job, result)));
    return result;
}

nlohmann::ordered_json photonMapRunRecord(const Scene& scene, const PhotonMapJob& job, const PhotonMapResult& r) {
    const PhotonMapSettings& s = job.settings;
    const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();
    const double render = r.renderSeconds();
    nlohmann::ordered_json record = {
        {"kind", "photon-map"},
        {"scene", jobSceneRecord(scene, job.scene, job.sceneParams)},
        {"settings",
         {{"width", s.width},
          {"height", s.height},
          {"photons", s.photons},
          {"k", s.k},
          {"maxRadius", s.maxRadius},
          {"spp", s.samplesPerPixel},
          {"bounces", s.bounces == PhotonMapSettings::kUnbounded ? nlohmann::ordered_json("unbounded") : nlohmann::ordered_json(s.bounces)},
          {"indirectOnly", s.indirectOnly},
          {"diffuseOnly", s.diffuseOnly},
          {"seed", s.seed},
          {"timeLimitSeconds", s.timeLimitSeconds},
          {"threads", threads},
          {"frame", s.frame},
          {"timeSeconds", scene.timeOfFrame(s.frame)}}},
        {"output", jobOutputRecord(job.output, job.toneMap)},
        {"result",
         {{"photonsEmitted", r.photonsEmitted},
          {"photonsStored", r.photonsStored},
          {"stoppedByTimeLimit", r.stoppedByTimeLimit},
          {"buildSeconds", r.buildSeconds},
          {"renderSeconds", render},
          {"traceSeconds", r.traceSeconds},
          {"treeSeconds", r.treeSeconds},
          {"gatherSeconds", r.gatherSeconds},
          {"rays", r.photonRays + r.cameraRays},
          {"photonRays", r.photonRays},
          {"cameraRays", r.cameraRays},
          {"photonsPerSecond", r.traceSeconds > 0.0 ? static_cast<double>(r.photonsEmitted) / r.traceSeconds : 0.0},
          {"raysPerSecond", render > 0.0 ? static_cast<double>(r.photonRays + r.cameraRays) / render : 0.0},
          {"gathers", r.gathers},
          {"shortGathers", r.shortGathers},
          {"meanGatherRadius", r.meanGatherRadius},
          {"invalidSamples", r.invalidSamples}}},
        {"memory",
         {{"bytesPerPhoton", sizeof(Photon)},
          {"mapBytes", r.mapBytes}}},
    };
    nlohmann::ordered_json renderer = jobLibraryVersions();
    renderer["nanoflann"] = fmt::format("{}.{}.{}", NANOFLANN_VERSION >> 8, (NANOFLANN_VERSION >> 4) & 0xf, NANOFLANN_VERSION & 0xf);
    record["renderer"] = renderer;
    return record;
}

}  // namespace bounce
