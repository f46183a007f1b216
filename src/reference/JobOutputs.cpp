#include "reference/JobOutputs.h"

#include "core/FileIo.h"

#include <embree3/rtcore_config.h>
#include <fmt/format.h>
#include <tbb/version.h>

namespace bounce {

Expected<ImageFormat> checkJobOutputs(const std::filesystem::path& output, const std::filesystem::path& stats) {
    BOUNCE_TRY(const ImageFormat format, imageFormatFor(output));
    BOUNCE_TRY_VOID(checkWritable(output));
    if (!stats.empty()) {
        if (stats.extension() != ".json") return makeError("{}: the run record is JSON: use a .json file name", stats.string());
        BOUNCE_TRY_VOID(checkWritable(stats));
    }
    return format;
}

Expected<void> writeJobOutputs(const std::filesystem::path& output, const std::filesystem::path& stats, ImageFormat format,
                               const Image& radiance, const ToneMap& toneMap, const nlohmann::ordered_json& record) {
    // The image and its run record are written together: a failure leaves neither.
    OutputFiles outputs;
    BOUNCE_TRY(std::string image, encodeImage(output, radiance, format == ImageFormat::Png ? toneMap : ToneMap{}));
    outputs.add(output, std::move(image));
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

}  // namespace bounce
