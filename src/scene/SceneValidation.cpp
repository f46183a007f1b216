// finalizeScene(): the checks every scene passes before a renderer sees it, whatever its source, so
// renderers can assume finite values, valid indices, unit normals and non-degenerate triangles.
#include "core/ImageIo.h"
#include "core/Log.h"
#include "scene/AreaTexture.h"
#include "scene/SceneLoader.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {

// A triangle is degenerate when the sine of its largest angle's supplement is below this, i.e. its
// area is below kDegenerateSine/2 of its longest edge squared: float normals of such triangles are noise.
constexpr float kDegenerateSine = 1e-6f;
// Up vectors closer than this (sine of the angle) to the view direction leave the camera's roll undefined.
constexpr float kMinUpSine = 1e-4f;

bool finite(float v) { return std::isfinite(v); }
bool finite(glm::vec2 v) { return finite(v.x) && finite(v.y); }
bool finite(glm::vec3 v) { return finite(v.x) && finite(v.y) && finite(v.z); }
bool finite(const glm::quat& q) { return finite(q.w) && finite(q.x) && finite(q.y) && finite(q.z); }
bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!finite(m[c][r])) return false;
    return true;
}
bool nonNegative(glm::vec3 v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }
bool inUnit(float v) { return v >= 0.0f && v <= 1.0f; }
bool inUnit(glm::vec3 v) { return inUnit(v.x) && inUnit(v.y) && inUnit(v.z); }

std::string label(const std::string& kind, const std::string& name, size_t index) {
    return name.empty() ? fmt::format("{} #{}", kind, index) : fmt::format("{} '{}'", kind, name);
}

Expected<void> checkTrack(TransformTrack& track, const std::string& where) {
    for (size_t k = 0; k < track.keys.size(); ++k) {
        TransformKey& key = track.keys[k];
        if (!finite(key.time) || !finite(key.translation) || !finite(key.rotation) || !finite(key.scale))
            return makeError("{}: animation key {} has a non-finite value", where, k);
        const float len = glm::length(key.rotation);
        if (len <= 0.0f) return makeError("{}: animation key {} has a zero rotation quaternion", where, k);
        key.rotation /= len;
        if (k > 0 && key.time < track.keys[k - 1].time)
            return makeError("{}: animation keys are not sorted by time (key {} at {} s after {} s)", where, k,
                             key.time, track.keys[k - 1].time);
    }
    return {};
}

Expected<void> finalizeMesh(Mesh& mesh, const std::string& where) {
    const size_t n = mesh.positions.size();
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        return makeError("{}: {} normals for {} positions", where, mesh.normals.size(), n);
    if (!mesh.uvs.empty() && mesh.uvs.size() != n)
        return makeError("{}: {} uvs for {} positions", where, mesh.uvs.size(), n);
    if (mesh.indices.size() % 3 != 0)
        return makeError("{}: index count {} is not a multiple of 3", where, mesh.indices.size());
    if (mesh.indices.empty()) return makeError("{}: mesh has no triangles", where);
    for (size_t i = 0; i < n; ++i)
        if (!finite(mesh.positions[i])) return makeError("{}: position {} is not finite", where, i);
    for (size_t i = 0; i < mesh.normals.size(); ++i)
        if (!finite(mesh.normals[i])) return makeError("{}: normal {} is not finite", where, i);
    for (size_t i = 0; i < mesh.uvs.size(); ++i)
        if (!finite(mesh.uvs[i])) return makeError("{}: uv {} is not finite", where, i);
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            return makeError("{}: index {} (triangle {}) is {}, out of range for {} vertices", where, i, i / 3,
                             mesh.indices[i], n);

    std::vector<uint32_t> kept;
    kept.reserve(mesh.indices.size());
    std::vector<glm::vec3> faceNormalSum(n, glm::vec3(0.0f));
    size_t dropped = 0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::vec3 e1 = mesh.positions[b] - mesh.positions[a];
        const glm::vec3 e2 = mesh.positions[c] - mesh.positions[a];
        const glm::vec3 e3 = mesh.positions[c] - mesh.positions[b];
        const glm::vec3 cr = glm::cross(e1, e2);  // twice the area, along the face normal
        const float longest2 = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
        if (!(glm::length(cr) > kDegenerateSine * longest2)) {
            ++dropped;
            continue;
        }
        kept.insert(kept.end(), {a, b, c});
        faceNormalSum[a] += cr;  // |cr| = 2 area: area weighting
        faceNormalSum[b] += cr;
        faceNormalSum[c] += cr;
    }
    if (kept.empty())
        return makeError("{}: every one of its {} triangles is degenerate (zero area)", where,
                         mesh.indices.size() / 3);
    if (dropped > 0)
        spdlog::warn("{}: dropped {} degenerate triangle(s) of {}", where, dropped, mesh.indices.size() / 3);
    mesh.indices = std::move(kept);

    if (mesh.normals.empty()) {
        mesh.normals.resize(n, glm::vec3(0.0f, 1.0f, 0.0f));
        for (size_t i = 0; i < n; ++i)
            if (glm::length(faceNormalSum[i]) > 0.0f) mesh.normals[i] = glm::normalize(faceNormalSum[i]);
    } else {
        size_t replaced = 0;
        for (size_t i = 0; i < n; ++i) {
            const float len = glm::length(mesh.normals[i]);
            if (len > 0.0f) {
                mesh.normals[i] /= len;
            } else if (glm::length(faceNormalSum[i]) > 0.0f) {
                mesh.normals[i] = glm::normalize(faceNormalSum[i]);
                ++replaced;
            } else {
                mesh.normals[i] = glm::vec3(0.0f, 1.0f, 0.0f);  // only on vertices no triangle uses
            }
        }
        if (replaced > 0) spdlog::warn("{}: replaced {} zero-length normal(s) by face normals", where, replaced);
    }
    return {};
}

Expected<void> checkLight(const Scene& scene, Light& light, const std::string& where) {
    if (!finite(light.position) || !finite(light.direction) || !finite(light.intensity) ||
        !finite(light.irradiance) || !finite(light.radiance) || !finite(light.cutoffAngle) ||
        !finite(light.falloffExponent) || !finite(light.edgeU) || !finite(light.edgeV))
        return makeError("{}: a value is not finite", where);
    if (!nonNegative(light.intensity)) return makeError("{}: negative intensity", where);
    if (!nonNegative(light.irradiance)) return makeError("{}: negative irradiance", where);
    if (!nonNegative(light.radiance)) return makeError("{}: negative radiance", where);
    switch (light.type) {
        case LightType::Spot:
            if (!(light.cutoffAngle > 0.0f) || light.cutoffAngle > glm::pi<float>())
                return makeError("{}: spot cutoff angle {} rad is outside (0, pi]", where, light.cutoffAngle);
            if (light.falloffExponent < 0.0f)
                return makeError("{}: negative spot falloff exponent {}", where, light.falloffExponent);
            [[fallthrough]];
        case LightType::Directional:
            if (!(glm::length(light.direction) > 0.0f)) return makeError("{}: zero direction", where);
            light.direction = glm::normalize(light.direction);
            break;
        case LightType::Area:
            if (!(light.area() > 0.0f)) return makeError("{}: area light has zero area", where);
            break;
        case LightType::Point: break;
    }
    if (light.twoSided && light.type != LightType::Area) return makeError("{}: only area lights can be two-sided", where);
    BOUNCE_TRY_VOID(checkAreaTexture(scene, light, where));
    return checkTrack(light.animation, where);
}

Expected<void> checkCamera(Camera& camera, const std::string& scene) {
    const std::string where = scene + ": camera";
    if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up) || !finite(camera.verticalFov) ||
        !finite(camera.orthoHeight) || !finite(camera.nearPlane) || !finite(camera.farPlane))
        return makeError("{}: a value is not finite", where);
    const glm::vec3 view = camera.target - camera.position;
    if (!(glm::length(view) > 0.0f)) return makeError("{}: position equals target", where);
    if (!(glm::length(camera.up) > 0.0f)) return makeError("{}: zero up vector", where);
    if (!(glm::length(glm::cross(glm::normalize(view), glm::normalize(camera.up))) > kMinUpSine))
        return makeError("{}: up vector is parallel to the view direction", where);
    camera.up = glm::normalize(camera.up);
    if (camera.projection == Projection::Perspective &&
        !(camera.verticalFov > 0.0f && camera.verticalFov < glm::pi<float>()))
        return makeError("{}: vertical field of view {} rad is outside (0, pi)", where, camera.verticalFov);
    if (camera.projection == Projection::Orthographic && !(camera.orthoHeight > 0.0f))
        return makeError("{}: orthographic height {} m is not positive", where, camera.orthoHeight);
    if (!(camera.nearPlane > 0.0f) || !(camera.farPlane > camera.nearPlane))
        return makeError("{}: clip planes near {} m, far {} m need 0 < near < far", where, camera.nearPlane,
                         camera.farPlane);
    return checkTrack(camera.animation, where);
}

}  // namespace

void computeTangents(Mesh& mesh) {
    // Per-triangle dp/du and dp/dv accumulated at the corners, area-weighted (the cross-product
    // denominator), then Gram-Schmidt against the vertex normal: the method of Lengyel (2001), which
    // assimp's aiProcess_CalcTangentSpace also uses; MikkTSpace differs only in how it splits seams.
    const size_t n = mesh.positions.size();
    std::vector<glm::vec3> dpdu(n, glm::vec3(0.0f)), dpdv(n, glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::vec3 e1 = mesh.positions[b] - mesh.positions[a], e2 = mesh.positions[c] - mesh.positions[a];
        const glm::vec2 d1 = mesh.uvs[b] - mesh.uvs[a], d2 = mesh.uvs[c] - mesh.uvs[a];
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 0.0f)) continue;  // no uv parametrisation on this triangle
        const float sign = det > 0.0f ? 1.0f : -1.0f;  // unnormalised: each triangle weighs by its area
        const glm::vec3 u = sign * (e1 * d2.y - e2 * d1.y), v = sign * (e2 * d1.x - e1 * d2.x);
        for (uint32_t k : {a, b, c}) {
            dpdu[k] += u;
            dpdv[k] += v;
        }
    }
    mesh.tangents.assign(n, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3 nn = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f, 1.0f, 0.0f);
        glm::vec3 t = dpdu[i] - nn * glm::dot(nn, dpdu[i]);
        if (!(glm::length(t) > 0.0f)) {  // no uvs here: any tangent perpendicular to the normal
            t = glm::cross(nn, std::abs(nn.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f));
        }
        t = glm::normalize(t);
        // The bitangent w * cross(n, t) points up the image (-v): glTF's +y of a normal map.
        const float w = glm::dot(glm::cross(nn, t), -dpdv[i]) < 0.0f ? -1.0f : 1.0f;
        mesh.tangents[i] = glm::vec4(t, w);
    }
}

Expected<void> finalizeScene(Scene& scene) {
    const std::string& s = scene.source.empty() ? scene.name : scene.source;
    if (scene.objects.empty()) return makeError("{}: scene has no objects", s);
    if (!finite(scene.frameRate) || !(scene.frameRate > 0.0f))
        return makeError("{}: frame rate {} is not positive", s, scene.frameRate);

    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const TextureImage& tex = scene.textures[i];
        const std::string where = fmt::format("{}: {}", s, label("texture", tex.name, i));
        if (tex.image.empty()) return makeError("{}: empty image", where);
        BOUNCE_TRY_VOID(checkFinite(tex.image, where));
    }
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        Material& m = scene.materials[i];
        const std::string where = fmt::format("{}: {}", s, label("material", m.name, i));
        if (!finite(m.baseColor) || !finite(m.emission) || !finite(m.roughness) || !finite(m.metallic) ||
            !finite(m.specularF0))
            return makeError("{}: a value is not finite", where);
        if (!inUnit(m.baseColor)) return makeError("{}: base colour outside [0, 1]", where);
        if (!nonNegative(m.emission)) return makeError("{}: negative emission", where);
        if (!inUnit(m.roughness)) return makeError("{}: roughness {} outside [0, 1]", where, m.roughness);
        if (!inUnit(m.metallic)) return makeError("{}: metallic {} outside [0, 1]", where, m.metallic);
        if (!inUnit(m.specularF0)) return makeError("{}: specularF0 {} outside [0, 1]", where, m.specularF0);
        if (m.baseColorTexture < -1 || m.baseColorTexture >= static_cast<int>(scene.textures.size()))
            return makeError("{}: texture index {} out of range ({} textures)", where, m.baseColorTexture,
                             scene.textures.size());
        if (m.emissionTexture < -1 || m.emissionTexture >= static_cast<int>(scene.textures.size()))
            return makeError("{}: emission texture index {} out of range ({} textures)", where, m.emissionTexture,
                             scene.textures.size());
        if (!finite(m.alpha) || !finite(m.alphaCutoff) || !finite(m.normalScale))
            return makeError("{}: a value is not finite", where);
        if (!inUnit(m.alpha)) return makeError("{}: alpha {} outside [0, 1]", where, m.alpha);
        if (!inUnit(m.alphaCutoff)) return makeError("{}: alphaCutoff {} outside [0, 1]", where, m.alphaCutoff);
        for (const auto& [index, what] : {std::pair{m.alphaTexture, "alpha"}, std::pair{m.normalTexture, "normal"},
                                          std::pair{m.metallicRoughnessTexture, "metallic-roughness"}})
            if (index < -1 || index >= static_cast<int>(scene.textures.size()))
                return makeError("{}: {} texture index {} out of range ({} textures)", where, what, index,
                                 scene.textures.size());
    }
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        Mesh& mesh = scene.meshes[i];
        // Name the objects using the mesh: that is what a scene author recognises.
        std::string users;
        for (const Object& o : scene.objects)
            if (o.mesh == i) users += (users.empty() ? "" : ", ") + fmt::format("'{}'", o.name);
        const std::string where = fmt::format("{}: {}{}", s, label("mesh", mesh.name, i),
                                              users.empty() ? "" : " (object " + users + ")");
        BOUNCE_TRY_VOID(finalizeMesh(mesh, where));
        if (!mesh.tangents.empty() && mesh.tangents.size() != mesh.positions.size())
            return makeError("{}: {} tangents for {} positions", where, mesh.tangents.size(), mesh.positions.size());
        bool normalMapped = false;
        for (const Object& o : scene.objects)
            if (o.mesh == i && o.material < scene.materials.size() && scene.materials[o.material].normalTexture >= 0)
                normalMapped = true;
        if (normalMapped && mesh.tangents.empty()) {
            if (mesh.uvs.empty())
                spdlog::warn("{}: normal-mapped material but no texture coordinates: the normal map is ignored", where);
            else
                computeTangents(mesh);
        }
    }
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        Object& o = scene.objects[i];
        if (o.name.empty()) o.name = fmt::format("object-{}", i);
        const std::string where = fmt::format("{}: object '{}'", s, o.name);
        if (o.mesh >= scene.meshes.size())
            return makeError("{}: mesh index {} out of range ({} meshes)", where, o.mesh, scene.meshes.size());
        if (o.material >= scene.materials.size())
            return makeError("{}: material index {} out of range ({} materials)", where, o.material,
                             scene.materials.size());
        if (!finite(o.transform)) return makeError("{}: transform is not finite", where);
        if (!(std::abs(glm::determinant(glm::mat3(o.transform))) > 0.0f))
            return makeError("{}: transform is singular", where);
        BOUNCE_TRY_VOID(checkTrack(o.animation, where));
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        Light& light = scene.lights[i];
        if (light.name.empty()) light.name = fmt::format("light-{}", i);
        BOUNCE_TRY_VOID(checkLight(scene, light, fmt::format("{}: light '{}'", s, light.name)));
    }
    BOUNCE_TRY_VOID(checkCamera(scene.camera, s));
    for (const auto& [key, value] : scene.settings)
        if (key.find('.') == std::string::npos || key.front() == '.' || key.back() == '.')
            return makeError("{}: setting '{}' is not of the form technique.setting", s, key);
    return {};
}

}  // namespace bounce
