#include "reference/PhotonMapJob.h"

#include "reference/JobOutputs.h"

#include <nanoflann.hpp>

namespace bounce {

Expected<PhotonMapResult> runPhotonMapJob(const Scene& scene, const PhotonMapJob& job,
                                          const PhotonMapProgressCallback& progress) {
    return runJobWithOutputs<PhotonMapResult>(
        job.output, job.stats, {}, job.toneMap, "a run record needs an output image",
        [&]() -> Expected<PhotonMapResult> {
            BOUNCE_TRY(const PhotonMapper mapper, PhotonMapper::create(scene, job.settings));
            return mapper.render(progress);
        },
        [&](const PhotonMapResult& result) { return photonMapRunRecord(scene, job, result); },
        [](const PhotonMapResult&) -> const Image* { return nullptr; });
}

nlohmann::ordered_json photonMapRunRecord(const Scene& scene, const PhotonMapJob& job, const PhotonMapResult& r) {
    const PhotonMapSettings& s = job.settings;
    const double render = r.renderSeconds();
    nlohmann::ordered_json settings = {{"width", s.width}, {"height", s.height}, {"photons", s.photons},
                                       {"k", s.k},         {"maxRadius", s.maxRadius}, {"spp", s.samplesPerPixel}};
    settings.update(jobScopeRecord(scene, s));
    nlohmann::ordered_json record = {
        {"kind", "photon-map"},
        {"scene", jobSceneRecord(scene, job.scene, job.sceneParams)},
        {"settings", settings},
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
