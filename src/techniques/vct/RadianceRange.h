#pragma once
// The automatic radiance range of vct's 8-bit volumes (docs/techniques/vct.md, "HDR radiance in 8-bit
// formats"), GL-free: fixed area-weighted surface samples of the scene, and the brightest radiance a
// Lambertian surface reflects at any of them under the lights, unshadowed (an upper bound of what the
// voxelizer injects, so the RGBA8 volumes never clip).
#include "scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace bounce::vct {

struct RangeSample {
    uint32_t object = 0;
    glm::vec3 position{0.0f}, normal{0.0f};  // object space
    float albedo = 0.0f;                     // largest diffuse channel; negative marks a two-sided surface
};

// `count` area-weighted points over every object's triangles at time 0, fixed seed (deterministic).
std::vector<RangeSample> rangeSamples(const Scene& scene, size_t count);

// max over the samples of albedo / pi * sum of the lights' unshadowed irradiance, W/(m^2 sr), with
// the objects placed at `time`; 0 without samples or light.
float brightestReflectedRadiance(const std::vector<RangeSample>& samples, const Scene& scene, const std::vector<Light>& lights,
                                 float time);

// Irradiance on a surface at x with normal n from light l, unshadowed, largest channel (area lights:
// the point approximation of the rectangle, capped by an infinite emitter's pi L).
float unshadowedIrradiance(const Light& l, glm::vec3 x, glm::vec3 n, bool twoSided);

}  // namespace bounce::vct
