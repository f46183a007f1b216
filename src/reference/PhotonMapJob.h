#pragma once
// One `bounce photon-map` run as a library call, like ReferenceJob: check that the image and the
// run record can be written, render with the photon mapper, write both atomically (a bad path fails
// before any work and leaves no file behind).
#include "core/Error.h"
#include "core/ToneMap.h"
#include "reference/PhotonMap.h"
#include "scene/SceneLoader.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace bounce {

struct PhotonMapJob {
    std::string scene;  // as asked for: built-in name or file path (for the record)
    SceneParams sceneParams;
    PhotonMapSettings settings;
    std::filesystem::path output;  // .exr: linear radiance; .png: tone-mapped with `toneMap`; empty: none written
    std::filesystem::path stats;   // run record (JSON); empty for none
    ToneMap toneMap;
};

Expected<PhotonMapResult> runPhotonMapJob(const Scene& scene, const PhotonMapJob& job,
                                          const PhotonMapProgressCallback& progress = {});

// The run record: the reference's fields where they mean the same (kind, scene, settings, output,
// result, renderer) plus the photon map's own. docs/techniques/photon-map.md lists them.
nlohmann::ordered_json photonMapRunRecord(const Scene& scene, const PhotonMapJob& job, const PhotonMapResult& result);

}  // namespace bounce
