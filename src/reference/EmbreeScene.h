#pragma once
// The scene's triangles at one instant, in world space, inside an Embree 3 BVH, together with the
// per-triangle data that shading needs (normals, uvs, material). Shared by the path tracer and the
// ray-casting service; not meant for use outside src/reference.
//
// Embree geometry ids are indices into geometries(): first one geometry per selected object, then
// (when asked) one two-triangle geometry per rectangular area light. A one-sided area light's
// rectangle is only there for rays arriving on its emitting side: from behind, rays pass through it;
// a two-sided light's rectangle is there from both sides.
#include "core/Error.h"
#include "reference/TextureLookup.h"
#include "scene/Scene.h"

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace bounce {

enum class GeometryFilter {
    StaticOnly,  // objects without animation only
    All,
};

struct EmbreeSceneOptions {
    float time = 0.0f;  // seconds; objects and lights are placed as at this time
    GeometryFilter filter = GeometryFilter::All;
    bool includeAreaLights = false;  // add the rectangles of LightType::Area lights as geometry
};

inline constexpr uint32_t kNoIndex = 0xffffffffu;

// Fills a single Embree ray (all geometry visible, no motion blur). Shared by the path tracer and
// the ray caster so both set rays up the same way.
inline void setRay(RTCRay& r, glm::vec3 origin, glm::vec3 direction, float tMin, float tMax) noexcept {
    r.org_x = origin.x;
    r.org_y = origin.y;
    r.org_z = origin.z;
    r.tnear = tMin;
    r.dir_x = direction.x;
    r.dir_y = direction.y;
    r.dir_z = direction.z;
    r.time = 0.0f;
    r.tfar = tMax;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
}

// An area light's rectangle is the triangles (0, 1, 2) and (0, 2, 3) of its corners at (u, v) = (0, 0),
// (1, 0), (1, 1), (0, 1) (Scene.h: position + (u - 1/2) edgeU + (v - 1/2) edgeV). This maps Embree's
// barycentrics (b1, b2) on triangle primId to the light's (u, v), exactly (no division).
inline glm::vec2 areaLightUv(uint32_t primId, float b1, float b2) noexcept {
    return primId == 0 ? glm::vec2(b1 + b2, b2) : glm::vec2(b1, b1 + b2);
}

struct SceneGeometry {
    enum class Kind : uint8_t { Object, AreaLight };
    Kind kind = Kind::Object;
    uint32_t objectIndex = kNoIndex;  // Scene::objects, for Kind::Object
    uint32_t materialIndex = kNoIndex;
    uint32_t lightIndex = kNoIndex;  // Scene::lights, for Kind::AreaLight
    bool twoSided = false;
    // World space at the build time. normals is empty when the mesh has none or when every vertex
    // normal equals its face normal (flat shading, e.g. boxes): faceNormals are used then. uvs is
    // empty when the mesh has none or its material has no texture, base colour or emission (nothing
    // reads them then).
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::uvec3> triangles;
    // Unit normal of the counter-clockwise winding (OpenGL's front face), and area in m^2.
    std::vector<glm::vec3> faceNormals;
    std::vector<float> areas;
    // Alpha masking (Material::masked): an intersection filter rejects hits where the coverage
    // alpha * coverage texel (bilinear, level 0, TextureLookup.h) is below alphaCutoff, for every ray.
    std::shared_ptr<const Image> alphaTexture;  // null: the factor alone
    float alpha = 1.0f;
    float alphaCutoff = 0.0f;  // 0: no filter
    // Normal map (Material::normalTexture): world tangents (xyz, w the bitangent sign) per vertex.
    std::shared_ptr<const Image> normalTexture;
    float normalScale = 1.0f;
    std::vector<glm::vec4> tangents;
};

// A point on a surface found by a ray.
struct SurfacePoint {
    glm::vec3 position;
    glm::vec3 geometricNormal;  // unit, front side (counter-clockwise winding)
    glm::vec3 shadingNormal;    // unit, interpolated vertex normal turned into the front hemisphere
    glm::vec2 uv;
};

// The textures the CPU renderers (PathTracer, PhotonMapper) read, checked before they build: every
// material texture index in range with a non-empty, finite image, and every light's area texture valid
// (checkAreaTexture).
Expected<void> checkTracedTextures(const Scene& scene);

class EmbreeScene {
public:
    static Expected<EmbreeScene> build(const Scene& scene, const EmbreeSceneOptions& options);

    RTCScene handle() const noexcept { return m_scene.get(); }
    const std::vector<SceneGeometry>& geometries() const noexcept { return m_geometries; }
    const SceneGeometry& geometry(uint32_t geomId) const noexcept { return m_geometries[geomId]; }
    float time() const noexcept { return m_time; }

    // (u, v) are Embree's barycentrics: p = (1-u-v) p0 + u p1 + v p2. Inline: it runs once per ray.
    SurfacePoint surface(uint32_t geomId, uint32_t primId, float u, float v) const noexcept {
        const SceneGeometry& g = m_geometries[geomId];
        const glm::uvec3 t = g.triangles[primId];
        const float w = 1.0f - u - v;
        SurfacePoint s;
        s.position = w * g.positions[t.x] + u * g.positions[t.y] + v * g.positions[t.z];
        s.geometricNormal = g.faceNormals[primId];
        s.shadingNormal = s.geometricNormal;
        if (!g.normals.empty()) {
            const glm::vec3 n = w * g.normals[t.x] + u * g.normals[t.y] + v * g.normals[t.z];
            const float len = glm::length(n);
            if (len > 0.0f) {
                s.shadingNormal = n / len;
                // A vertex normal more than 90 degrees from its face belongs to the other side (a
                // mirroring transform, or a normal authored for the back face): keep it consistent.
                if (glm::dot(s.shadingNormal, s.geometricNormal) < 0.0f) s.shadingNormal = -s.shadingNormal;
            }
        }
        s.uv = g.uvs.empty() ? glm::vec2(0.0f) : w * g.uvs[t.x] + u * g.uvs[t.y] + v * g.uvs[t.z];
        if (g.normalTexture && !g.tangents.empty() && !g.uvs.empty())
            s.shadingNormal = normalMapped(g, t, w, u, v, s.shadingNormal, s.uv);
        return s;
    }

    // The tangent-space normal map applied to the front-side shading normal n, exactly as
    // shaders/common/scene.glsl's materialNormal: normalize(T x + B y + N z), T orthogonalised
    // against n, B = w cross(n, T), the map's x and y times the normal scale.
    static glm::vec3 normalMapped(const SceneGeometry& g, glm::uvec3 t, float w, float u, float v, glm::vec3 n,
                                  glm::vec2 uv) noexcept {
        const glm::vec4 tw = w * g.tangents[t.x] + u * g.tangents[t.y] + v * g.tangents[t.z];
        if (tw.w == 0.0f) return n;
        glm::vec3 tangent = glm::vec3(tw) - n * glm::dot(n, glm::vec3(tw));
        const float len = glm::length(tangent);
        if (!(len > 0.0f)) return n;
        tangent /= len;
        const glm::vec3 bitangent = tw.w * glm::cross(n, tangent);
        glm::vec3 m = lookupBilinearRepeat(*g.normalTexture, uv) * 2.0f - 1.0f;
        m.x *= g.normalScale;
        m.y *= g.normalScale;
        const glm::vec3 mapped = tangent * m.x + bitangent * m.y + n * m.z;
        const float ml = glm::length(mapped);
        return ml > 0.0f ? mapped / ml : n;
    }

private:
    struct DeviceDeleter {
        void operator()(RTCDeviceTy* d) const noexcept { rtcReleaseDevice(d); }
    };
    struct SceneDeleter {
        void operator()(RTCSceneTy* s) const noexcept { rtcReleaseScene(s); }
    };

    EmbreeScene() = default;

    std::unique_ptr<RTCDeviceTy, DeviceDeleter> m_device;
    std::unique_ptr<RTCSceneTy, SceneDeleter> m_scene;
    std::vector<SceneGeometry> m_geometries;
    float m_time = 0.0f;
};

}  // namespace bounce
