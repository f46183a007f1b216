#include "reference/EmbreeScene.h"

#include "core/ImageIo.h"
#include "core/Log.h"
#include "scene/AreaTexture.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cstring>

namespace bounce {

namespace {

// Let Embree use 256-bit kernels and a BVH8 where the CPU has them. Its default on AVX-512 Xeons
// ("simd128", to keep clocks high for SIMD-heavy host code) builds a BVH4; bounce's own tracing code
// is scalar, so that caution buys nothing: on cornell-box-area the BVH8 traced 7-15% more paths per
// second (interleaved runs on the 2-core Skylake Xeon of docs/reference.md "Performance").
constexpr const char* kDeviceConfig = "frequency_level=simd256";

// Below this many triangles the BVH is built at RTC_BUILD_QUALITY_LOW. Measured with
// `bounce reference` and the path-tracer benchmark (docs/reference.md "Performance"): LOW traces
// 34 % more paths per second on cornell-box-area (38 triangles) and 10 % more on two-rooms; the two
// are level on atrium at 1,916 to 10,000 triangles, and HIGH is 12-17 % faster at 20,000 and 100,000.
constexpr size_t kSmallSceneTriangles = 1024;

void onEmbreeError(void* /*user*/, RTCError code, const char* message) {
    spdlog::error("embree: error {}: {}", static_cast<int>(code), message ? message : "");
}

void computeFaceData(SceneGeometry& g) {
    g.faceNormals.resize(g.triangles.size());
    g.areas.resize(g.triangles.size());
    for (size_t i = 0; i < g.triangles.size(); ++i) {
        const glm::uvec3 t = g.triangles[i];
        const glm::vec3 c = glm::cross(g.positions[t.y] - g.positions[t.x], g.positions[t.z] - g.positions[t.x]);
        const float len = glm::length(c);
        // A degenerate triangle is never hit (Embree skips it) and never sampled (area 0).
        g.faceNormals[i] = len > 0.0f ? c / len : glm::vec3(0.0f, 0.0f, 1.0f);
        g.areas[i] = 0.5f * len;
    }
}

// True when every vertex normal equals the face normal of each triangle using it (within float
// rounding of a normalised vector), so interpolation would only reproduce the face normal.
bool isFlat(const SceneGeometry& g) {
    constexpr float kSameDirection = 0.99999f;  // cos of 0.26 degrees
    for (size_t i = 0; i < g.triangles.size(); ++i) {
        if (!(g.areas[i] > 0.0f)) continue;
        const glm::uvec3 t = g.triangles[i];
        const glm::vec3 n = g.faceNormals[i];
        if (glm::dot(g.normals[t.x], n) < kSameDirection || glm::dot(g.normals[t.y], n) < kSameDirection ||
            glm::dot(g.normals[t.z], n) < kSameDirection)
            return false;
    }
    return true;
}

// One-sided area lights are emitters that are not meshes (docs/scene.md "Lights"): seen from behind
// they do not exist, for every kind of ray. Embree calls this for candidate hits on their rectangles
// (two-sided lights have no filter: both sides are there).
void passThroughBackOfAreaLight(const RTCFilterFunctionNArguments* args) {
    const auto* normal = static_cast<const glm::vec3*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const float cosine = RTCRayN_dir_x(args->ray, args->N, i) * normal->x +
                             RTCRayN_dir_y(args->ray, args->N, i) * normal->y +
                             RTCRayN_dir_z(args->ray, args->N, i) * normal->z;
        if (cosine >= 0.0f) args->valid[i] = 0;
    }
}

// Alpha-masked materials (docs/scene.md "Materials"): a candidate hit where the coverage is below the
// cutoff is no hit, for camera, bounce, shadow and photon rays alike (the rasterizer discards the
// same texels in every pass).
void rejectMaskedHits(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const SceneGeometry*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        const glm::uvec3 t = g->triangles[prim];
        const glm::vec2 uv = (1.0f - u - v) * g->uvs[t.x] + u * g->uvs[t.y] + v * g->uvs[t.z];
        const float sample = g->alphaTexture ? lookupBilinearRepeat(*g->alphaTexture, uv).r : 1.0f;
        if (!(g->alpha * sample >= g->alphaCutoff)) args->valid[i] = 0;
    }
}

Expected<void> attach(RTCDevice device, RTCScene scene, const SceneGeometry& g, unsigned id) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geom) return makeError("embree: cannot create a triangle geometry");
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), g.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), g.triangles.size()));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geom);
        return makeError("embree: out of memory for {} vertices", g.positions.size());
    }
    std::memcpy(vertices, g.positions.data(), g.positions.size() * sizeof(glm::vec3));
    std::memcpy(indices, g.triangles.data(), g.triangles.size() * sizeof(glm::uvec3));
    if (g.kind == SceneGeometry::Kind::AreaLight && !g.twoSided) {
        // The user pointer stays valid: faceNormals' buffer moves with the EmbreeScene.
        rtcSetGeometryUserData(geom, const_cast<glm::vec3*>(g.faceNormals.data()));
        rtcSetGeometryIntersectFilterFunction(geom, passThroughBackOfAreaLight);
        rtcSetGeometryOccludedFilterFunction(geom, passThroughBackOfAreaLight);
    }
    if (g.kind == SceneGeometry::Kind::Object && g.alphaCutoff > 0.0f && !g.uvs.empty()) {
        // The geometry stays at this address: m_geometries' buffer moves with the EmbreeScene.
        rtcSetGeometryUserData(geom, const_cast<SceneGeometry*>(&g));
        rtcSetGeometryIntersectFilterFunction(geom, rejectMaskedHits);
        rtcSetGeometryOccludedFilterFunction(geom, rejectMaskedHits);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, id);
    rtcReleaseGeometry(geom);
    return {};
}

}  // namespace

Expected<void> checkTracedTextures(const Scene& scene) {
    for (const Material& m : scene.materials)
        for (const int index : {m.baseColorTexture, m.emissionTexture}) {
            if (index < 0) continue;
            if (static_cast<size_t>(index) >= scene.textures.size())
                return makeError("material '{}': texture index {} out of range ({} textures)", m.name, index,
                                 scene.textures.size());
            const TextureImage& t = scene.textures[static_cast<size_t>(index)];
            if (t.image.empty()) return makeError("texture '{}' (material '{}'): empty image", t.name, m.name);
            BOUNCE_TRY_VOID(checkFinite(t.image, "texture '" + t.name + "'"));
        }
    for (const Light& light : scene.lights)
        BOUNCE_TRY_VOID(checkAreaTexture(scene, light, "light '" + light.name + "'"));
    return {};
}

Expected<EmbreeScene> EmbreeScene::build(const Scene& scene, const EmbreeSceneOptions& options) {
    EmbreeScene out;
    out.m_time = options.time;
    out.m_device.reset(rtcNewDevice(kDeviceConfig));
    if (!out.m_device) return makeError("embree: cannot create a device (error {})", static_cast<int>(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(out.m_device.get(), onEmbreeError, nullptr);
    // Each texture an alpha mask or normal map reads is copied once, shared by the geometries using it
    // (the EmbreeScene must not depend on the Scene outliving it).
    std::vector<std::shared_ptr<const Image>> textureCopies(scene.textures.size());
    const auto textureCopy = [&](int index) -> std::shared_ptr<const Image> {
        if (index < 0 || static_cast<size_t>(index) >= scene.textures.size()) return nullptr;
        auto& copy = textureCopies[static_cast<size_t>(index)];
        if (!copy) copy = std::make_shared<const Image>(scene.textures[static_cast<size_t>(index)].image);
        return copy;
    };

    for (size_t oi = 0; oi < scene.objects.size(); ++oi) {
        const Object& object = scene.objects[oi];
        if (options.filter == GeometryFilter::StaticOnly && object.isDynamic()) continue;
        if (object.mesh >= scene.meshes.size())
            return makeError("object '{}': mesh index {} out of range ({} meshes)", object.name, object.mesh,
                             scene.meshes.size());
        if (object.material >= scene.materials.size())
            return makeError("object '{}': material index {} out of range ({} materials)", object.name,
                             object.material, scene.materials.size());
        const Mesh& mesh = scene.meshes[object.mesh];
        if (mesh.triangleCount() == 0) continue;
        const bool hasNormals = mesh.normals.size() == mesh.positions.size();
        const bool hasUvs = mesh.uvs.size() == mesh.positions.size();
        for (uint32_t index : mesh.indices)
            if (index >= mesh.positions.size())
                return makeError("mesh '{}': vertex index {} out of range ({} vertices)", mesh.name, index,
                                 mesh.positions.size());

        SceneGeometry g;
        g.kind = SceneGeometry::Kind::Object;
        g.objectIndex = static_cast<uint32_t>(oi);
        g.materialIndex = object.material;
        g.twoSided = scene.materials[object.material].twoSided;
        const glm::mat4 worldFromObject = object.worldFromObject(options.time);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(worldFromObject)));
        g.positions.reserve(mesh.positions.size());
        for (const glm::vec3& p : mesh.positions) g.positions.push_back(glm::vec3(worldFromObject * glm::vec4(p, 1.0f)));
        if (hasNormals) {
            g.normals.reserve(mesh.normals.size());
            for (const glm::vec3& n : mesh.normals) {
                const glm::vec3 w = normalMatrix * n;
                const float len = glm::length(w);
                g.normals.push_back(len > 0.0f ? w / len : glm::vec3(0.0f));
            }
        }
        const Material& material = scene.materials[object.material];
        const bool normalMapped = material.normalTexture >= 0 && mesh.tangents.size() == mesh.positions.size();
        if (hasUvs && (material.baseColorTexture >= 0 || material.emissionTexture >= 0 || material.masked() ||
                       normalMapped || material.metallicRoughnessTexture >= 0))
            g.uvs = mesh.uvs;
        if (material.masked()) {
            if (!hasUvs && material.alphaTexture >= 0)
                spdlog::warn("object '{}': alpha-masked material '{}' but no texture coordinates: the mask is its "
                             "factor alone", object.name, material.name);
            g.alphaTexture = hasUvs ? textureCopy(material.alphaTexture) : nullptr;
            g.alpha = g.alphaTexture || material.alpha < 1.0f ? material.alpha : 1.0f;
            g.alphaCutoff = material.alphaCutoff;
            if (!hasUvs) g.uvs.assign(mesh.positions.size(), glm::vec2(0.0f));
        }
        if (normalMapped && hasUvs) {
            g.normalTexture = textureCopy(material.normalTexture);
            g.normalScale = material.normalScale;
            const glm::mat3 linear(worldFromObject);
            g.tangents.reserve(mesh.tangents.size());
            for (const glm::vec4& tn : mesh.tangents) g.tangents.push_back(glm::vec4(linear * glm::vec3(tn), tn.w));
        }
        g.triangles.resize(mesh.triangleCount());
        std::memcpy(g.triangles.data(), mesh.indices.data(), g.triangles.size() * sizeof(glm::uvec3));
        computeFaceData(g);
        if (hasNormals && isFlat(g) && !g.normalTexture) g.normals.clear();
        out.m_geometries.push_back(std::move(g));
    }

    if (options.includeAreaLights) {
        for (size_t li = 0; li < scene.lights.size(); ++li) {
            if (scene.lights[li].type != LightType::Area) continue;
            const Light light = scene.lights[li].at(options.time);
            if (!(light.area() > 0.0f)) return makeError("light '{}': area light with zero area", light.name);
            SceneGeometry g;
            g.kind = SceneGeometry::Kind::AreaLight;
            g.lightIndex = static_cast<uint32_t>(li);
            g.twoSided = light.twoSided;
            const glm::vec3 c = light.position, hu = 0.5f * light.edgeU, hv = 0.5f * light.edgeV;
            // Counter-clockwise seen from the emitting side, so faceNormals equal areaNormal().
            g.positions = {c - hu - hv, c + hu - hv, c + hu + hv, c - hu + hv};
            g.triangles = {glm::uvec3(0, 1, 2), glm::uvec3(0, 2, 3)};
            computeFaceData(g);
            out.m_geometries.push_back(std::move(g));
        }
    }

    out.m_scene.reset(rtcNewScene(out.m_device.get()));
    if (!out.m_scene) return makeError("embree: cannot create a scene");
    // The BVH is built once per render and traced billions of times: spend on quality, except for
    // tiny scenes, where Embree's fast (Morton) build traces faster than its high-quality one.
    size_t triangles = 0;
    for (const SceneGeometry& g : out.m_geometries) triangles += g.triangles.size();
    rtcSetSceneBuildQuality(out.m_scene.get(),
                            triangles < kSmallSceneTriangles ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
    for (size_t i = 0; i < out.m_geometries.size(); ++i)
        BOUNCE_TRY_VOID(attach(out.m_device.get(), out.m_scene.get(), out.m_geometries[i], static_cast<unsigned>(i)));
    rtcCommitScene(out.m_scene.get());
    const RTCError error = rtcGetDeviceError(out.m_device.get());
    if (error != RTC_ERROR_NONE) return makeError("embree: building the BVH failed (error {})", static_cast<int>(error));
    return out;
}

}  // namespace bounce
