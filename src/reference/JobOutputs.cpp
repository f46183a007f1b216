#include "reference/JobOutputs.h"

#include "core/FileIo.h"

#include <embree3/rtcore_config.h>
#include <fmt/format.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>

namespace bounce {

Expected<ImageFormat> checkJobOutputs(const std::filesystem::path& output, const std::filesystem::path& stats,
                                      const std::filesystem::path& variance) {
    BOUNCE_TRY(const ImageFormat format, imageFormatFor(output));
    BOUNCE_TRY_VOID(checkWritable(output));
    if (!stats.empty()) {
        if (stats.extension() != ".json") return makeError("{}: the run record is JSON: use a .json file name", stats.string());
        BOUNCE_TRY_VOID(checkWritable(stats));
    }
    if (!variance.empty()) {
        if (variance.extension() != ".exr")
            return makeError("{}: the variance image holds linear values: use an .exr file name", variance.string());
        BOUNCE_TRY_VOID(checkWritable(variance));
    }
    return format;
}

Expected<void> writeJobOutputs(const std::filesystem::path& output, const std::filesystem::path& stats, ImageFormat format,
                               const Image& radiance, const ToneMap& toneMap, const nlohmann::ordered_json& record,
                               const std::filesystem::path& variancePath, const Image* variance) {
    // The image, its variance and its run record are written together: a failure leaves none of them.
    OutputFiles outputs;
    BOUNCE_TRY(std::string image, encodeImage(output, radiance, format == ImageFormat::Png ? toneMap : ToneMap{}));
    outputs.add(output, std::move(image));
    if (!variancePath.empty() && variance) {
        BOUNCE_TRY(std::string bytes, encodeImage(variancePath, *variance, ToneMap{}));
        outputs.add(variancePath, std::move(bytes));
    }
    if (!stats.empty()) outputs.add(stats, record.dump(2) + "\n");
    return outputs.commit();
}

nlohmann::ordered_json jobSceneRecord(const Scene& scene, const std::string& asked, const SceneParams& params) {
    nlohmann::ordered_json p = nlohmann::ordered_json::object();
    for (const auto& [key, value] : params) p[key] = value;
    return {{"name", scene.name}, {"source", scene.source}, {"asked", asked}, {"params", p}};
}

nlohmann::ordered_json jobOutputRecord(const std::filesystem::path& output, const ToneMap& toneMap) {
    nlohmann::ordered_json out = {{"path", output.string()}};
    if (auto format = imageFormatFor(output); format && *format == ImageFormat::Png)
        out["toneMap"] = {{"curve", toneCurveName(toneMap.curve)}, {"exposureEv", toneMap.exposureEv}};
    return out;
}

nlohmann::ordered_json jobLibraryVersions() {
    return {{"embree", fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH)}, {"tbb", TBB_VERSION_STRING}};
}

nlohmann::ordered_json jobScopeRecord(const Scene& scene, int bounces, bool unbounded, bool indirectOnly, bool diffuseOnly,
                                      uint64_t seed, double timeLimitSeconds, int threads, uint32_t frame) {
    return {{"bounces", unbounded ? nlohmann::ordered_json("unbounded") : nlohmann::ordered_json(bounces)},
            {"indirectOnly", indirectOnly},
            {"diffuseOnly", diffuseOnly},
            {"seed", seed},
            {"timeLimitSeconds", timeLimitSeconds},
            {"threads", threads > 0 ? threads : tbb::info::default_concurrency()},
            {"frame", frame},
            {"timeSeconds", scene.timeOfFrame(frame)}};
}

}  // namespace bounce
