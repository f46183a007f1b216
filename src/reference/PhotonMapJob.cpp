#include "reference/PhotonMapJob.h"

#include "core/FileIo.h"
#include "core/ImageIo.h"

#include <embree3/rtcore_config.h>
#include <nanoflann.hpp>
#include <tbb/task_arena.h>
#include <tbb/version.h>

namespace bounce {

Expected<PhotonMapResult> runPhotonMapJob(const Scene& scene, const PhotonMapJob& job,
                                          const PhotonMapProgressCallback& progress) {
    BOUNCE_TRY(const ImageFormat format, imageFormatFor(job.output));
    BOUNCE_TRY_VOID(checkWritable(job.output));
    if (!job.stats.empty()) {
        if (job.stats.extension() != ".json")
            return makeError("{}: the run record is JSON: use a .json file name", job.stats.string());
        BOUNCE_TRY_VOID(checkWritable(job.stats));
    }
    BOUNCE_TRY(const PhotonMapper mapper, PhotonMapper::create(scene, job.settings));
    PhotonMapResult result = mapper.render(progress);
    const ToneMap toneMap = format == ImageFormat::Png ? job.toneMap : ToneMap{};
    BOUNCE_TRY_VOID(writeImage(job.output, result.radiance, toneMap));
    if (!job.stats.empty())
        BOUNCE_TRY_VOID(writeTextFileAtomic(job.stats, photonMapRunRecord(scene, job, result).dump(2) + "\n"));
    return result;
}

nlohmann::ordered_json photonMapRunRecord(const Scene& scene, const PhotonMapJob& job, const PhotonMapResult& r) {
    const PhotonMapSettings& s = job.settings;
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (const auto& [key, value] : job.sceneParams) params[key] = value;
    nlohmann::ordered_json output = {{"path", job.output.string()}};
    if (auto format = imageFormatFor(job.output); format && *format == ImageFormat::Png)
        output["toneMap"] = {{"curve", toneCurveName(job.toneMap.curve)}, {"exposureEv", job.toneMap.exposureEv}};
    const int threads = s.threads > 0 ? s.threads : tbb::info::default_concurrency();
    const double render = r.renderSeconds();
    return {
        {"kind", "photon-map"},
        {"scene", {{"name", scene.name}, {"source", scene.source}, {"asked", job.scene}, {"params", params}}},
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
        {"output", output},
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
        {"renderer",
         {{"embree", fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH)},
          {"tbb", TBB_VERSION_STRING},
          {"nanoflann", fmt::format("{}.{}.{}", NANOFLANN_VERSION >> 8, (NANOFLANN_VERSION >> 4) & 0xf, NANOFLANN_VERSION & 0xf)}}},
    };
}

}  // namespace bounce
