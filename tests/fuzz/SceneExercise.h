#pragma once
// What the scene and model fuzz targets do with a scene that loaded (passed finalizeScene): what
// `bounce render` and `bounce reference` read from it first, at a tiny size. The camera, the lights and
// the bounds at several times (animations are evaluated between and beyond their keys), and a 4x4
// path-traced image with one sample, which builds Embree's BVH over every triangle and the light
// sampler over every light and emissive material. Validation exists so that none of this can fail:
// a scene that loaded must give finite matrices and finite samples.
#include "FuzzSupport.h"
#include "reference/PathTracer.h"
#include "scene/Scene.h"

#include <glm/gtc/matrix_access.hpp>

#include <cmath>

namespace bounce::fuzz {

inline bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

inline void exerciseScene(const Scene& scene) {
    // Frame 0, the next frame, and one far past any key (tracks clamp or loop there).
    for (const uint32_t frame : {0u, 1u, 1000u}) {
        const float t = scene.timeOfFrame(frame);
        glm::vec3 lo, hi;
        scene.bounds(t, lo, hi);
        const Camera camera = scene.camera.at(t);
        if (!finite(camera.viewFromWorld()) || !finite(camera.clipFromView(1.0f)))
            invariantBroken("a validated scene's camera gave a non-finite view or projection matrix");
        for (const Light& light : scene.lights) {
            const glm::vec3 flux = light.at(t).flux();
            if (!std::isfinite(flux.x) || !std::isfinite(flux.y) || !std::isfinite(flux.z))
                invariantBroken("a validated scene's light has a non-finite flux");
        }
    }
    PathTracerSettings settings;
    settings.width = 4;
    settings.height = 4;
    settings.samplesPerPixel = 1;
    settings.bounces = 2;
    settings.threads = 1;  // no thread pool per input
    auto tracer = PathTracer::create(scene, settings);
    if (!tracer) return;  // refused with a message (a scene the reference cannot render): not a finding
    const PathTracerResult result = tracer->render();
    if (result.invalidSamples != 0) invariantBroken("a validated scene gave non-finite path-traced samples");
}

}  // namespace bounce::fuzz
