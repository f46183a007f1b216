#pragma once
// Next-event estimation for the reference path tracer: one list of every light source in the scene
// (point, spot and directional lights, rectangular area lights and each triangle of every object
// whose material emits), from which one is picked per shading point with probability proportional
// to its emitted flux (luminance). Triangles of one emissive object therefore get area-weighted
// probabilities; a point on a rectangle or triangle is then chosen uniformly by area.
//
// Directional lights have no finite flux: they are weighted by the flux that crosses the disc of
// the scene's bounding sphere, pi R^2 E (pbrt's convention for distant lights).
#include "reference/EmbreeScene.h"
#include "reference/Sampling.h"
#include "scene/Scene.h"

#include <vector>

namespace bounce {

struct LightSample {
    glm::vec3 wi;            // unit direction from the shading point towards the light
    float distance;          // to the sampled point; infinity for directional lights
    glm::vec3 lightPoint;    // shadow-ray end, already moved off the emitting surface
    glm::vec3 contribution;  // incident radiance (delta lights: irradiance at normal incidence) / pdf
    float pdf;               // solid-angle pdf including the light choice; 0 for delta lights
};

class LightSampler {
public:
    LightSampler(const Scene& scene, const EmbreeScene& embree);

    size_t lightCount() const noexcept { return m_entries.size(); }
    bool empty() const noexcept { return m_entries.empty(); }

    // Samples a light as seen from point p. Returns false when the chosen light sends nothing
    // towards p (behind a one-sided emitter, outside a spot cone).
    bool sample(glm::vec3 p, float uSelect, float u1, float u2, LightSample& out) const noexcept;

    // Solid-angle pdf with which sample() would have produced a point on triangle primId of
    // geometry geomId, seen at `distance` under cosine `cosLight` (absolute value) at the light.
    float pdfEmitterHit(uint32_t geomId, uint32_t primId, float distance, float cosLight) const noexcept;

private:
    enum class Kind : uint8_t { Point, Spot, Directional, Area, Triangle };
    struct Entry {
        Kind kind;
        bool twoSided = false;
        glm::vec3 position{0.0f};  // point, spot; area and triangle: a corner
        glm::vec3 edge1{0.0f};     // area, triangle
        glm::vec3 edge2{0.0f};
        glm::vec3 normal{0.0f};    // spot axis, directional propagation direction, emitter normal
        glm::vec3 emitted{0.0f};   // intensity W/sr, irradiance W/m^2 or radiance W/(m^2 sr)
        float area = 0.0f;
        float cosCutoff = 0.0f;  // spot
        float exponent = 1.0f;   // spot
    };

    void add(const Entry& entry, float weight);

    std::vector<Entry> m_entries;
    std::vector<float> m_weights;  // unnormalised during construction
    std::vector<float> m_cdf;      // inclusive, last = 1
    std::vector<float> m_pmf;
    // Per Embree geometry: the first entry of an emissive object's triangles (entry = base + primId),
    // the entry of an area light, or kNoIndex.
    std::vector<uint32_t> m_entryOfGeometry;
};

}  // namespace bounce
