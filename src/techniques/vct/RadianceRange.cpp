// vct's automatic radiance range (RadianceRange.h).
#include "techniques/vct/RadianceRange.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace bounce::vct {

namespace {
// Fixed seed of the surface samples: the range is a deterministic function of the scene.
constexpr uint32_t kRangeSeed = 1234u;
}  // namespace

float unshadowedIrradiance(const Light& l, glm::vec3 x, glm::vec3 n, bool twoSided) {
    auto cosine = [&](glm::vec3 toLight) {
        const float c = glm::dot(n, toLight);
        return twoSided ? std::abs(c) : std::max(c, 0.0f);
    };
    auto maxc = [](glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); };
    switch (l.type) {
        case LightType::Directional: return maxc(l.irradiance) * cosine(-glm::normalize(l.direction));
        case LightType::Area: {
            const glm::vec3 d = l.position - x;
            const float r2 = std::max(glm::dot(d, d), 1e-8f);
            const glm::vec3 w = d / std::sqrt(r2);
            const float area = glm::length(glm::cross(l.edgeU, l.edgeV));
            const float cosL = std::max(glm::dot(-w, l.areaNormal()), 0.0f);
            // Point approximation of the rectangle, capped by the irradiance of an infinite emitter.
            return std::min(maxc(l.radiance) * area * cosL * cosine(w) / r2, glm::pi<float>() * maxc(l.radiance));
        }
        case LightType::Point:
        case LightType::Spot: {
            const glm::vec3 d = l.position - x;
            const float r2 = std::max(glm::dot(d, d), 1e-8f);
            const glm::vec3 w = d / std::sqrt(r2);
            float intensity = maxc(l.intensity);
            if (l.type == LightType::Spot) {
                const float cosA = glm::dot(-w, glm::normalize(l.direction));
                if (cosA < std::cos(l.cutoffAngle) || cosA <= 0.0f) return 0.0f;
                intensity *= std::pow(cosA, l.falloffExponent);
            }
            return intensity * cosine(w) / r2;
        }
    }
    return 0.0f;
}


std::vector<RangeSample> rangeSamples(const Scene& scene, size_t count) {
    std::vector<RangeSample> out;
    double totalArea = 0.0;
    std::vector<double> areas;
    std::vector<std::pair<uint32_t, uint32_t>> tris;  // (object, first index)
    for (uint32_t o = 0; o < scene.objects.size(); ++o) {
        const Object& obj = scene.objects[o];
        // Alpha-masked surfaces (foliage cards) are left out: where they exist needs their texture,
        // and a range taken from texels that are not there would rescale every other voxel.
        if (scene.materials[obj.material].masked()) continue;
        const Mesh& m = scene.meshes[obj.mesh];
        const glm::mat4 w = obj.worldFromObject(0.0f);
        for (uint32_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::vec3 a = glm::vec3(w * glm::vec4(m.positions[m.indices[i]], 1.0f));
            const glm::vec3 b = glm::vec3(w * glm::vec4(m.positions[m.indices[i + 1]], 1.0f));
            const glm::vec3 c = glm::vec3(w * glm::vec4(m.positions[m.indices[i + 2]], 1.0f));
            const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
            areas.push_back(area);
            tris.emplace_back(o, i);
            totalArea += area;
        }
    }
    if (totalArea > 0.0) {
        std::mt19937 rng(kRangeSeed);
        std::discrete_distribution<size_t> pick(areas.begin(), areas.end());
        std::uniform_real_distribution<float> u01(0.0f, 1.0f);
        for (size_t k = 0; k < count; ++k) {
            const auto [o, i] = tris[pick(rng)];
            const Object& obj = scene.objects[o];
            const Mesh& m = scene.meshes[obj.mesh];
            const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
            float s = u01(rng), t = u01(rng);
            if (s + t > 1.0f) s = 1.0f - s, t = 1.0f - t;
            const Material& mat = scene.materials[obj.material];
            RangeSample r;
            r.object = o;
            r.position = a + s * (b - a) + t * (c - a);
            r.normal = glm::normalize(glm::cross(b - a, c - a));
            r.albedo = std::max(mat.baseColor.x, std::max(mat.baseColor.y, mat.baseColor.z)) * (1.0f - mat.metallic);
            if (mat.twoSided) r.albedo = -r.albedo;  // sign marks two-sided surfaces
            out.push_back(r);
        }
    }
    return out;
}

float brightestReflectedRadiance(const std::vector<RangeSample>& samples, const Scene& scene, const std::vector<Light>& lights,
                                 float time) {
    std::vector<glm::mat4> transforms(scene.objects.size()), normals(scene.objects.size());
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        transforms[o] = scene.objects[o].worldFromObject(time);
        normals[o] = glm::transpose(glm::inverse(transforms[o]));
    }
    float brightest = 0.0f;
    for (const RangeSample& s : samples) {
        const glm::vec3 x = glm::vec3(transforms[s.object] * glm::vec4(s.position, 1.0f));
        const glm::vec3 n = glm::normalize(glm::vec3(normals[s.object] * glm::vec4(s.normal, 0.0f)));
        float e = 0.0f;
        for (const Light& l : lights) e += unshadowedIrradiance(l, x, n, s.albedo < 0.0f);
        brightest = std::max(brightest, std::abs(s.albedo) / glm::pi<float>() * e);
    }
    return brightest;
}

}  // namespace bounce::vct
