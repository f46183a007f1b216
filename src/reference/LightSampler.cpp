#include "reference/LightSampler.h"

#include "core/Image.h"
#include "scene/AreaTexture.h"

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
    m_textureOfGeometry.assign(embree.geometries().size(), nullptr);
    for (size_t gi = 0; gi < embree.geometries().size(); ++gi) {
        const SceneGeometry& g = embree.geometries()[gi];
        if (g.kind == SceneGeometry::Kind::AreaLight) {
            const Light light = scene.lights[g.lightIndex].at(time);
            // The texture shown at this instant (a sequence's frame, the bouncing square's position).
            Image scratch;
            const Image* image = areaTextureAt(scene, light, time, scratch);
            const EmitterTexture* texture = nullptr;
            if (image) {
                m_textures.push_back(std::make_unique<EmitterTexture>(*image, light.radiance));
                texture = m_textures.back().get();
                m_textureOfGeometry[gi] = texture;
            }
            // pi L A per side; a texture replaces lum(L) by the mean of lum(L * texel).
            const float sides = light.twoSided ? 2.0f : 1.0f;
            const float emittedLuminance = texture ? texture->meanLuminance() : luminance(light.radiance);
            const float power = sides * (kPi * emittedLuminance * light.area());
            if (!(power > 0.0f)) {
                // A black frame: no power now, never chosen, and emits nothing where rays hit it.
                if (texture && luminance(light.radiance) > 0.0f) m_darkTexturedLight = true;
                continue;
            }
            Entry e{Kind::Area};
            e.twoSided = light.twoSided;
            e.position = g.positions[0];
            e.edge1 = light.edgeU;
            e.edge2 = light.edgeV;
            e.normal = g.faceNormals[0];
            e.emitted = light.radiance;
            e.area = light.area();
            e.texture = texture;
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
            if (material.emissionTexture >= 0) {
                // A mesh without uvs reads the texel at (0, 0) everywhere, as its hits do (and the GPU).
                e.emissionTexture = &scene.textures[static_cast<size_t>(material.emissionTexture)].image;
                if (!g.uvs.empty()) {
                    e.uv0 = g.uvs[tri.x];
                    e.uv1 = g.uvs[tri.y] - g.uvs[tri.x];
                    e.uv2 = g.uvs[tri.z] - g.uvs[tri.x];
                }
            }
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
    if (!(total > 0.0)) {
        // Nothing can be chosen: empty() then means "no light at all" (at this instant, when
        // hasDarkTexturedLight()).
        m_entries.clear();
        m_entryOfGeometry.assign(m_entryOfGeometry.size(), kNoIndex);
        return;
    }
    const size_t n = m_weights.size();
    for (size_t i = 0; i < n; ++i) m_entries[i].pmf = static_cast<float>(m_weights[i] / total);

    // Vose's alias method: scaled weights n * pmf below 1 are topped up by one entry above 1.
    m_aliasTable.resize(n);
    std::vector<double> scaled(n);
    std::vector<uint32_t> small, large;
    for (size_t i = 0; i < n; ++i) {
        m_aliasTable[i].alias = static_cast<uint32_t>(i);
        scaled[i] = static_cast<double>(m_weights[i]) / total * static_cast<double>(n);
        (scaled[i] < 1.0 ? small : large).push_back(static_cast<uint32_t>(i));
    }
    while (!small.empty() && !large.empty()) {
        const uint32_t s = small.back(), l = large.back();
        small.pop_back();
        m_aliasTable[s].threshold = static_cast<float>(scaled[s]);
        m_aliasTable[s].alias = l;
        scaled[l] -= 1.0 - scaled[s];
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // Leftovers are 1 up to rounding: they keep themselves (threshold 1).
}

}  // namespace bounce
