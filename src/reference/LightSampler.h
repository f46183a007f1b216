#pragma once
// Next-event estimation for the reference path tracer: one list of every light source in the scene
// (point, spot and directional lights, rectangular area lights and each triangle of every object
// whose material emits), from which one is picked per shading point with probability proportional
// to its emitted flux (luminance), in constant time through an alias table. Triangles of one emissive object therefore get area-weighted
// probabilities; a point on a triangle or an untextured rectangle is then chosen uniformly by area, a
// point on a textured rectangle by its texels' emitted luminance (EmitterTexture.h), so the pdf of a
// textured light carries the chosen texel's factor. Two-sided rectangles and triangles count both
// sides' flux and are sampled from whichever side faces the shading point.
//
// Directional lights have no finite flux: they are weighted by the flux that crosses the disc of
// the scene's bounding sphere, pi R^2 E (pbrt's convention for distant lights).
#include "reference/EmbreeScene.h"
#include "reference/EmitterTexture.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"
#include "scene/Scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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
    // Public for the path tracer's vectorised kernel, which reads emitters lane by lane.
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
        float pmf = 0.0f;        // probability of being chosen
        const EmitterTexture* texture = nullptr;  // area: emission multiplier and its distribution, or null
        // Triangle of a material with an emission texture: the texture (bilinear, repeating) and the uvs
        // at `position` and along the edges; the point at barycentrics (b1, b2) has uv uv0 + b1 uv1 + b2 uv2.
        const Image* emissionTexture = nullptr;
        glm::vec2 uv0{0.0f}, uv1{0.0f}, uv2{0.0f};
    };
    struct AliasSlot {
        float threshold = 1.0f;  // keep the slot's own entry below this, else take `alias`
        uint32_t alias = 0;
    };

    LightSampler(const Scene& scene, const EmbreeScene& embree);

    size_t lightCount() const noexcept { return m_entries.size(); }
    bool empty() const noexcept { return m_entries.empty(); }
    // True when the scene has a textured area light of non-zero radiance whose texture is black at this
    // instant (a dark frame of a sequence): such a light has no power now and is never chosen, and the
    // scene is lit after all at other times, so an empty list is then not a scene without lights.
    bool hasDarkTexturedLight() const noexcept { return m_darkTexturedLight; }

    // Samples a light as seen from point p. Returns false when the chosen light sends nothing
    // towards p (behind a one-sided emitter, outside a spot cone).
    bool sample(glm::vec3 p, float uSelect, float u1, float u2, LightSample& out) const noexcept;

    // Solid-angle pdf with which sample() would have produced the point at Embree barycentrics (u, v) of
    // triangle primId of geometry geomId, seen at `distance` under cosine `cosLight` (absolute value) at
    // the light.
    float pdfEmitterHit(uint32_t geomId, uint32_t primId, float u, float v, float distance, float cosLight) const noexcept;
    // The emission texture of Embree geometry geomId (a textured area light's rectangle), or null.
    const EmitterTexture* texture(uint32_t geomId) const noexcept { return m_textureOfGeometry[geomId]; }
    // For the vectorised kernel, which samples rectangles uniformly in (u1, u2) and triangles by
    // uniformTriangle(u1, u2): remaps the numbers of a textured rectangle to the texel-distributed point,
    // and returns the entry's emitted radiance and pmf at the point, the same numbers sample() uses (a
    // triangle with an emission texture: the texel there, pmf unchanged).
    static void textureSample(const Entry& e, float& u1, float& u2, glm::vec3& emitted, float& pmf) noexcept;

    // The entry sample() picks for uSelect.
    const Entry& choose(float uSelect) const noexcept;
    // The entry of triangle primId of geometry geomId if it emits, else null.
    const Entry* emitter(uint32_t geomId, uint32_t primId) const noexcept;

private:
    void add(const Entry& entry, float weight);

    std::vector<Entry> m_entries;
    std::vector<float> m_weights;  // unnormalised flux, for construction
    // Walker's alias table (built with Vose's method): O(1) choice without a branchy search.
    std::vector<AliasSlot> m_aliasTable;
    // Per Embree geometry: the first entry of an emissive object's triangles (entry = base + primId),
    // the entry of an area light, or kNoIndex.
    std::vector<uint32_t> m_entryOfGeometry;
    // Textured area lights at this instant; entries and m_textureOfGeometry point into them (the
    // pointers survive moves of the sampler).
    std::vector<std::unique_ptr<EmitterTexture>> m_textures;
    std::vector<const EmitterTexture*> m_textureOfGeometry;  // per Embree geometry
    bool m_darkTexturedLight = false;
};

inline void LightSampler::textureSample(const Entry& e, float& u1, float& u2, glm::vec3& emitted, float& pmf) noexcept {
    emitted = e.emitted;
    pmf = e.pmf;
    if (e.emissionTexture) {
        // Points on an emissive triangle stay uniform by area (the choice ignores the texture: unbiased,
        // if noisier where the texture is dark); only the radiance there changes.
        const glm::vec2 b = uniformTriangle(u1, u2);
        emitted = e.emitted * lookupBilinearRepeat(*e.emissionTexture, e.uv0 + b.x * e.uv1 + b.y * e.uv2);
        return;
    }
    if (!e.texture) return;
    const EmitterTexture::Sample s = e.texture->sample(u1, u2);
    // The rectangle's corner is (u, v) = (0, 0) and its edges are edgeU, edgeV (EmbreeScene's layout).
    u1 = s.uv.x;
    u2 = s.uv.y;
    emitted = e.emitted * e.texture->texel(s.texel);
    pmf = e.pmf * e.texture->pdf(s.texel);
}

inline const LightSampler::Entry& LightSampler::choose(float uSelect) const noexcept {
    const float scaled = uSelect * static_cast<float>(m_entries.size());
    const size_t slot = std::min(static_cast<size_t>(scaled), m_entries.size() - 1);
    const float u = scaled - static_cast<float>(slot);
    const AliasSlot& a = m_aliasTable[slot];
    return m_entries[u < a.threshold ? slot : a.alias];
}

inline bool LightSampler::sample(glm::vec3 p, float uSelect, float u1, float u2, LightSample& out) const noexcept {
    const Entry& e = choose(uSelect);
    const float pmf = e.pmf;
    if (!(pmf > 0.0f)) return false;
    switch (e.kind) {
        case Kind::Point:
        case Kind::Spot: {
            const glm::vec3 toLight = e.position - p;
            const float d2 = glm::dot(toLight, toLight);
            if (!(d2 > 0.0f)) return false;
            const float d = std::sqrt(d2);
            out.wi = toLight * (1.0f / d);
            out.distance = d;
            out.lightPoint = e.position;
            out.pdf = 0.0f;
            glm::vec3 intensity = e.emitted;
            if (e.kind == Kind::Spot) {
                const float cosAlpha = -glm::dot(out.wi, e.normal);
                if (!(cosAlpha > e.cosCutoff) || cosAlpha <= 0.0f) return false;
                intensity *= std::pow(cosAlpha, e.exponent);
            }
            out.contribution = intensity * (1.0f / (d2 * pmf));
            return true;
        }
        case Kind::Directional:
            out.wi = -e.normal;
            out.distance = std::numeric_limits<float>::infinity();
            out.lightPoint = p;
            out.pdf = 0.0f;
            out.contribution = e.emitted * (1.0f / pmf);
            return true;
        case Kind::Area:
        case Kind::Triangle: {
            glm::vec3 y;
            glm::vec3 emitted = e.emitted;
            float pdfChoice = pmf;  // pmf, times the texel's density on a textured rectangle
            textureSample(e, u1, u2, emitted, pdfChoice);
            if (e.kind == Kind::Area) {
                y = e.position + u1 * e.edge1 + u2 * e.edge2;
            } else {
                const glm::vec2 b = uniformTriangle(u1, u2);
                y = e.position + b.x * e.edge1 + b.y * e.edge2;
            }
            const glm::vec3 toLight = y - p;
            const float d2 = glm::dot(toLight, toLight);
            if (!(d2 > 0.0f)) return false;
            const float d = std::sqrt(d2);
            const float invD = 1.0f / d;
            out.wi = toLight * invD;
            float cosLight = -glm::dot(out.wi, e.normal);
            const bool front = cosLight > 0.0f;
            if (!front) {
                if (!e.twoSided) return false;
                cosLight = -cosLight;
            }
            if (!(cosLight > 0.0f)) return false;
            out.distance = d;
            out.lightPoint = offsetRayOrigin(y, front ? e.normal : -e.normal);
            // pdf = pmf d^2 / (A cos); the contribution Le / pdf reuses 1/d instead of dividing again.
            out.pdf = pdfChoice * d2 / (e.area * cosLight);
            out.contribution = emitted * (e.area * cosLight * invD * invD / pdfChoice);
            return true;
        }
    }
    return false;
}

inline const LightSampler::Entry* LightSampler::emitter(uint32_t geomId, uint32_t primId) const noexcept {
    uint32_t index = m_entryOfGeometry[geomId];
    if (index == kNoIndex || m_entries.empty()) return nullptr;
    if (m_entries[index].kind == Kind::Triangle) index += primId;
    return &m_entries[index];
}

inline float LightSampler::pdfEmitterHit(uint32_t geomId, uint32_t primId, float u, float v, float distance,
                                        float cosLight) const noexcept {
    const Entry* e = emitter(geomId, primId);
    if (!e || !(cosLight > 0.0f) || !(e->area > 0.0f)) return 0.0f;
    const float texel = e->texture ? e->texture->pdf(e->texture->texelAt(areaLightUv(primId, u, v))) : 1.0f;
    return e->pmf * texel * distance * distance / (e->area * cosLight);
}

}  // namespace bounce
