#pragma once
// JSON scene files (format: docs/scene.md "JSON scene files"): models placed with transforms and
// optional material overrides, materials, lights, camera, keyframe animations, frame rate and default
// technique settings. Paths inside are relative to the JSON file.
#include "core/Error.h"
#include "scene/Scene.h"

#include <filesystem>

namespace bounce {

// Reads and places everything; the result is not finalized (loadScene does that).
Expected<Scene> loadJsonScene(const std::filesystem::path& path);

}  // namespace bounce
