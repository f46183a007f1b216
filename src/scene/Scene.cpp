#include "scene/Scene.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {

namespace {

glm::vec3 catmullRom(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float s) {
    const float s2 = s * s, s3 = s2 * s;
    return 0.5f * ((2.0f * p1) + (-p0 + p2) * s + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * s2 +
                   (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * s3);
}

glm::mat4 compose(glm::vec3 t, glm::quat r, glm::vec3 s) {
    return glm::translate(glm::mat4(1.0f), t) * glm::toMat4(r) * glm::scale(glm::mat4(1.0f), s);
}

}  // namespace

glm::mat4 TransformTrack::evaluate(float t) const {
    if (keys.empty()) return glm::mat4(1.0f);
    if (keys.size() == 1) return compose(keys[0].translation, keys[0].rotation, keys[0].scale);
    const float t0 = keys.front().time, t1 = keys.back().time;
    const float span = t1 - t0;
    if (loop && span > 0.0f) {
        t = t0 + std::fmod(t - t0, span);
        if (t < t0) t += span;
    }
    t = std::clamp(t, t0, t1);
    size_t i = 0;
    while (i + 2 < keys.size() && keys[i + 1].time <= t) ++i;
    const TransformKey& a = keys[i];
    const TransformKey& b = keys[i + 1];
    const float dt = b.time - a.time;
    const float s = dt > 0.0f ? std::clamp((t - a.time) / dt, 0.0f, 1.0f) : 0.0f;
    glm::vec3 translation;
    if (interpolation == Interpolation::CatmullRom) {
        // Neighbours beyond the ends: wrap for loops (the last key repeats the first), else clamp.
        const size_t n = keys.size();
        auto at = [&](ptrdiff_t k) -> glm::vec3 {
            if (loop) {
                const ptrdiff_t m = static_cast<ptrdiff_t>(n) - 1;  // distinct keys when closed
                k = ((k % m) + m) % m;
            } else {
                k = std::clamp<ptrdiff_t>(k, 0, static_cast<ptrdiff_t>(n) - 1);
            }
            return keys[static_cast<size_t>(k)].translation;
        };
        const auto ii = static_cast<ptrdiff_t>(i);
        translation = catmullRom(at(ii - 1), at(ii), at(ii + 1), at(ii + 2), s);
    } else {
        translation = glm::mix(a.translation, b.translation, s);
    }
    return compose(translation, glm::slerp(a.rotation, b.rotation, s), glm::mix(a.scale, b.scale, s));
}

Light Light::at(float t) const {
    if (animation.empty()) return *this;
    const glm::mat4 m = animation.evaluate(t);
    const glm::mat3 r(m);
    Light out = *this;
    out.position = glm::vec3(m * glm::vec4(position, 1.0f));
    out.direction = glm::normalize(r * direction);
    out.edgeU = r * edgeU;
    out.edgeV = r * edgeV;
    return out;
}

glm::vec3 Light::areaNormal() const { return glm::normalize(glm::cross(edgeU, edgeV)); }

float Light::area() const { return glm::length(glm::cross(edgeU, edgeV)); }

glm::vec3 Light::flux() const {
    constexpr float pi = glm::pi<float>();
    switch (type) {
        case LightType::Point: return 4.0f * pi * intensity;
        case LightType::Spot: {
            // Integral of cos^n over the cone: 2*pi*(1 - cos^(n+1) c)/(n+1).
            const float n = falloffExponent;
            const float c = std::cos(std::min(cutoffAngle, pi / 2.0f));
            // Cutoffs past 90 degrees add nothing: bounce clamps cos(alpha) at 0 (docs/scene.md).
            const float solid = 2.0f * pi * (1.0f - std::pow(c, n + 1.0f)) / (n + 1.0f);
            return intensity * solid;
        }
        case LightType::Area: return (twoSided ? 2.0f : 1.0f) * pi * radiance * area();
        case LightType::Directional: return glm::vec3(0.0f);
    }
    return glm::vec3(0.0f);
}

Camera Camera::at(float t) const {
    if (animation.empty()) return *this;
    const glm::mat4 m = animation.evaluate(t);
    Camera out = *this;
    out.position = glm::vec3(m * glm::vec4(position, 1.0f));
    out.target = glm::vec3(m * glm::vec4(target, 1.0f));
    out.up = glm::normalize(glm::mat3(m) * up);
    return out;
}

glm::mat4 Camera::viewFromWorld() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::clipFromView(float aspect) const {
    if (projection == Projection::Orthographic) {
        const float h = 0.5f * orthoHeight, w = h * aspect;
        return glm::ortho(-w, w, -h, h, nearPlane, farPlane);
    }
    return glm::perspective(verticalFov, aspect, nearPlane, farPlane);
}

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const Object& o : objects) n += meshes[o.mesh].triangleCount();
    return n;
}

bool Scene::hasEmissiveMaterials() const {
    return std::any_of(materials.begin(), materials.end(),
                       [](const Material& m) { return glm::any(glm::greaterThan(m.emission, glm::vec3(0.0f))); });
}

bool Scene::emitsLight() const {
    const auto positive = [](glm::vec3 v) { return glm::any(glm::greaterThan(v, glm::vec3(0.0f))); };
    for (const Light& l : lights) {
        switch (l.type) {
            case LightType::Point:
            case LightType::Spot:
                if (positive(l.intensity)) return true;
                break;
            case LightType::Directional:
                if (positive(l.irradiance)) return true;
                break;
            case LightType::Area:
                if (positive(l.radiance)) return true;
                break;
        }
    }
    return hasEmissiveMaterials();
}

void Scene::bounds(float t, glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(-std::numeric_limits<float>::max());
    for (const Object& o : objects) {
        const glm::mat4 m = o.worldFromObject(t);
        for (const glm::vec3& p : meshes[o.mesh].positions) {
            const glm::vec3 w = glm::vec3(m * glm::vec4(p, 1.0f));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
    if (objects.empty()) lo = hi = glm::vec3(0.0f);
}

}  // namespace bounce
