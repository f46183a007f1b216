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

}  // namespace bounce
