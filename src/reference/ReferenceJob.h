#pragma once
// One `bounce reference` run as a library call: render a scene with the path tracer and write the
// image and the run record, atomically and only after checking that both can be written (a bad
// path fails before any rendering and leaves no file behind).
#include "core/Error.h"
#include "core/ToneMap.h"
#include "reference/PathTracer.h"
#include "scene/SceneLoader.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace bounce {

struct ReferenceJob {
    std::string scene;  // as asked for: built-in name or file path (for the record)
    SceneParams sceneParams;
    PathTracerSettings settings;
    std::filesystem::path output;  // .exr: linear radiance; .png: tone-mapped with `toneMap`
    std::filesystem::path stats;   // run record (JSON); empty for none
    ToneMap toneMap;
};

// Checks the output paths, renders `scene` (already loaded from job.scene) and writes the outputs.
Expected<PathTracerResult> runReferenceJob(const Scene& scene, const ReferenceJob& job,
                                           const ProgressCallback& progress = {});

// The run record: scene, settings, what was reached (samples, time, paths/s, rays/s) and the noise
// left. docs/reference.md "Run record" lists the fields.
nlohmann::ordered_json referenceRunRecord(const Scene& scene, const ReferenceJob& job, const PathTracerResult& result);

}  // namespace bounce
