#include "reference/LightSampler.h"

#include "core/Image.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {

void LightSampler::add(const Entry& entry, float weight) {
    m_entries.push_back(entry);
    m_weights.push_back(weight);
}

LightSampler::LightSampler(const Scene& scene, const EmbreeScene& embree) {
    const float time = embree.time();
    glm::vec3 lo, hi;
    scene.bounds(time, lo, hi);
    const float sceneRadius = 0.5f * glm::length(hi - lo);

    m_entryOfGeometry.assign(embree.geometries().size(), kNoIndex);
    for (size_t gi = 0; gi < embree.geometries().size(); ++gi) {
        const SceneGeometry& g = embree.geometries()[gi];
        if (g.kind == SceneGeometry::Kind::AreaLight) {
            const Light light = scene.lights[g.lightIndex].at(time);
            const float power = kPi * luminance(light.radiance) * light.area();
            if (!(power > 0.0f)) continue;
            Entry e{Kind::Area};
            e.position = g.positions[0];
            e.edge1 = light.edgeU;
            e.edge2 = light.edgeV;
            e.normal = g.faceNormals[0];
            e.emitted = light.radiance;
            e.area = light.area();
            m_entryOfGeometry[gi] = static_cast<uint32_t>(m_entries.size());
            add(e, power);
            continue;
        }
        const Material& material = scene.materials[g.materialIndex];
        const float radianceLum = luminance(material.emission);
        if (!(radianceLum > 0.0f)) continue;
        // One entry per triangle, so entry = base + primId; degenerate ones get weight 0.
        m_entryOfGeometry[gi] = static_cast<uint32_t>(m_entries.size());
        const float sides = g.twoSided ? 2.0f : 1.0f;
        for (size_t t = 0; t < g.triangles.size(); ++t) {
            const glm::uvec3 tri = g.triangles[t];
            Entry e{Kind::Triangle};
            e.twoSided = g.twoSided;
            e.position = g.positions[tri.x];
            e.edge1 = g.positions[tri.y] - g.positions[tri.x];
            e.edge2 = g.positions[tri.z] - g.positions[tri.x];
            e.normal = g.faceNormals[t];
            e.emitted = material.emission;
            e.area = g.areas[t];
            add(e, sides * kPi * radianceLum * e.area);
        }
    }

    for (const Light& original : scene.lights) {
        const Light light = original.at(time);
        Entry e{};
        float power = 0.0f;
        switch (light.type) {
            case LightType::Point:
                e.kind = Kind::Point;
                e.position = light.position;
                e.emitted = light.intensity;
                power = luminance(light.flux());
                break;
            case LightType::Spot:
                e.kind = Kind::Spot;
                e.position = light.position;
                e.normal = glm::normalize(light.direction);
                e.emitted = light.intensity;
                e.cosCutoff = std::cos(light.cutoffAngle);
                e.exponent = light.falloffExponent;
                power = luminance(light.flux());
                break;
            case LightType::Directional:
                e.kind = Kind::Directional;
                e.normal = glm::normalize(light.direction);
                e.emitted = light.irradiance;
                power = kPi * sceneRadius * sceneRadius * luminance(light.irradiance);
                break;
            case LightType::Area: continue;  // added with its geometry above
        }
        if (power > 0.0f) add(e, power);
    }

    double total = 0.0;
    for (float w : m_weights) total += w;
    m_cdf.resize(m_weights.size());
    m_pmf.resize(m_weights.size());
    double running = 0.0;
    for (size_t i = 0; i < m_weights.size(); ++i) {
        running += m_weights[i];
        m_pmf[i] = static_cast<float>(m_weights[i] / total);
        m_cdf[i] = static_cast<float>(running / total);
    }
    if (!m_cdf.empty()) m_cdf.back() = 1.0f;
    // Drop the light sources that can never be chosen so that empty() means "no light at all".
    if (total <= 0.0) {
        m_entries.clear();
        m_cdf.clear();
        m_pmf.clear();
    }
}

bool LightSampler::sample(glm::vec3 p, float uSelect, float u1, float u2, LightSample& out) const noexcept {
    const size_t index = std::min(static_cast<size_t>(std::upper_bound(m_cdf.begin(), m_cdf.end(), uSelect) - m_cdf.begin()),
                                  m_cdf.size() - 1);
    const Entry& e = m_entries[index];
    const float pmf = m_pmf[index];
    if (!(pmf > 0.0f)) return false;
    switch (e.kind) {
        case Kind::Point:
        case Kind::Spot: {
            const glm::vec3 toLight = e.position - p;
            const float d2 = glm::dot(toLight, toLight);
            if (!(d2 > 0.0f)) return false;
            const float d = std::sqrt(d2);
            out.wi = toLight / d;
            out.distance = d;
            out.lightPoint = e.position;
            out.pdf = 0.0f;
            glm::vec3 intensity = e.emitted;
            if (e.kind == Kind::Spot) {
                const float cosAlpha = -glm::dot(out.wi, e.normal);
                if (!(cosAlpha > e.cosCutoff) || cosAlpha <= 0.0f) return false;
                intensity *= std::pow(cosAlpha, e.exponent);
            }
            out.contribution = intensity / (d2 * pmf);
            return true;
        }
        case Kind::Directional:
            out.wi = -e.normal;
            out.distance = std::numeric_limits<float>::infinity();
            out.lightPoint = p;
            out.pdf = 0.0f;
            out.contribution = e.emitted / pmf;
            return true;
        case Kind::Area:
        case Kind::Triangle: {
            glm::vec3 y;
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
            out.wi = toLight / d;
            float cosLight = -glm::dot(out.wi, e.normal);
            const bool front = cosLight > 0.0f;
            if (!front) {
                if (!e.twoSided) return false;
                cosLight = -cosLight;
            }
            if (!(cosLight > 0.0f)) return false;
            out.distance = d;
            out.lightPoint = offsetRayOrigin(y, front ? e.normal : -e.normal);
            out.pdf = pmf * d2 / (e.area * cosLight);
            out.contribution = e.emitted / out.pdf;
            return true;
        }
    }
    return false;
}

float LightSampler::pdfEmitterHit(uint32_t geomId, uint32_t primId, float distance, float cosLight) const noexcept {
    uint32_t index = m_entryOfGeometry[geomId];
    if (index == kNoIndex || m_pmf.empty()) return 0.0f;
    if (m_entries[index].kind == Kind::Triangle) index += primId;
    const Entry& e = m_entries[index];
    if (!(cosLight > 0.0f) || !(e.area > 0.0f)) return 0.0f;
    return m_pmf[index] * distance * distance / (e.area * cosLight);
}

}  // namespace bounce
