#pragma once
// The first surface each pixel centre sees through the scene's camera: what the rasteriser's
// G-buffer holds there (CameraRays inverts the same projection), computed without a GPU. `bounce
// compare --leak-scene` makes a scene's leak masks from it for images it did not render.
#include "core/Error.h"
#include "core/Image.h"
#include "scene/Scene.h"

#include <cstdint>
#include <vector>

namespace bounce {

struct PrimaryHits {
    Image positions;               // world position of the hit, 0 where the ray hits nothing
    std::vector<uint8_t> covered;  // 1 where the ray hit a surface, row-major like `positions`
};

// Rays through the centres of a width x height image's pixels (top row first) at `time` seconds.
Expected<PrimaryHits> primaryHits(const Scene& scene, float time, int width, int height);

}  // namespace bounce
