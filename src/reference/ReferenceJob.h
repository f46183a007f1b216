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
#include <functional>
#include <string>

namespace bounce {

struct ReferenceJob {
    std::string scene;  // as asked for: built-in name or file path (for the record)
    SceneParams sceneParams;
    PathTracerSettings settings;
    // .exr: linear radiance; .png: tone-mapped with `toneMap`. Empty: nothing is written (the caller
    // keeps the result, as `import bounce` does); `stats` and `variance` must then be empty too.
    std::filesystem::path output;
    std::filesystem::path stats;     // run record (JSON); empty for none
    std::filesystem::path variance;  // .exr: PathTracerResult::variance (the noise floors' input); empty for none
    ToneMap toneMap;
    // Adds what this layer does not compute (the app's noise floors) to the run record before it is written.
    std::function<void(nlohmann::ordered_json& record, const PathTracerResult& result)> amendRecord;
};

// Checks the output paths, renders `scene` (already loaded from job.scene) and writes the outputs
// (image, variance image and run record together: a failure leaves none of them).
Expected<PathTracerResult> runReferenceJob(const Scene& scene, const ReferenceJob& job,
                                           const ProgressCallback& progress = {});

// The run record: scene, settings, what was reached (samples, time, paths/s, rays/s) and the noise
// left. docs/reference.md "Run record" lists the fields.
nlohmann::ordered_json referenceRunRecord(const Scene& scene, const ReferenceJob& job, const PathTracerResult& result);

}  // namespace bounce
