#include "render/ShadowCascades.h"

#include <algorithm>
#include <cmath>

namespace bounce::render {

namespace {

// Practical split scheme (Zhang et al. 2006, "Parallel-split shadow maps"): split distances are the
// mean of the logarithmic (lambda 1) and the uniform (lambda 0) schemes; 0.5 is their recommended value.
constexpr float kPracticalSplitLambda = 0.5f;
// A cascade's bounding radius is rounded up to the next power of 2^(1/8) (9 % steps), so its texel
// size stays constant while the camera moves within the scene (the far split follows the scene's
// depth range) and only changes in steps (bounce's choice: stability over a few % of resolution).
constexpr float kRadiusStepsPerOctave = 8.0f;

}  // namespace

ShadowCascades fitShadowCascades(const glm::mat4& baseClipFromWorld, float baseHalfExtent, const View& camera,
                                 glm::vec3 sceneLo, glm::vec3 sceneHi, int viewCascades, int tileSize) {
    ShadowCascades out;
    const float baseTexel = 2.0f * baseHalfExtent / static_cast<float>(tileSize);
    const auto finish = [&](int views) {
        out.cascades[views] = glm::vec4(0.0f, 0.0f, 1.0f, baseTexel);
        out.count = views + 1;
        return out;
    };
    viewCascades = std::clamp(viewCascades, 0, SHADOW_MAX_CASCADES - 1);
    if (viewCascades == 0 || tileSize < 8) return finish(0);

    // The scene's depth range in the camera's view (view depth = -z in view space).
    float minDepth = INFINITY, maxDepth = -INFINITY;
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner((k & 1) ? sceneHi.x : sceneLo.x, (k & 2) ? sceneHi.y : sceneLo.y,
                               (k & 4) ? sceneHi.z : sceneLo.z);
        const float depth = -(camera.viewFromWorld * glm::vec4(corner, 1.0f)).z;
        minDepth = std::min(minDepth, depth);
        maxDepth = std::max(maxDepth, depth);
    }
    const float nearDepth = std::max(camera.nearPlane, minDepth);
    const float farDepth = std::min(camera.farPlane, maxDepth);
    if (!(farDepth > nearDepth)) return finish(0);  // the scene is behind the camera

    // The frustum's corner rays: where each meets the near and the far plane.
    const glm::mat4 worldFromClip = glm::inverse(camera.clipFromWorld());
    glm::vec3 nearCorner[4], farCorner[4];
    for (int k = 0; k < 4; ++k) {
        const glm::vec2 ndc((k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f);
        const glm::vec4 n = worldFromClip * glm::vec4(ndc, -1.0f, 1.0f);
        const glm::vec4 f = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
        nearCorner[k] = glm::vec3(n) / n.w;
        farCorner[k] = glm::vec3(f) / f.w;
    }
    const auto at = [&](int k, float depth) {  // view depth is linear along each corner ray
        const float t = (depth - camera.nearPlane) / (camera.farPlane - camera.nearPlane);
        return nearCorner[k] + (farCorner[k] - nearCorner[k]) * t;
    };

    // The scene's box in the whole-scene map's uv: a slice reaching past the scene (the far one, a wide
    // view) is fitted to the part of it over the scene.
    glm::vec2 sceneUvLo(INFINITY), sceneUvHi(-INFINITY);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner((k & 1) ? sceneHi.x : sceneLo.x, (k & 2) ? sceneHi.y : sceneLo.y,
                               (k & 4) ? sceneHi.z : sceneLo.z);
        const glm::vec4 clip = baseClipFromWorld * glm::vec4(corner, 1.0f);
        const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
        sceneUvLo = glm::min(sceneUvLo, uv);
        sceneUvHi = glm::max(sceneUvHi, uv);
    }
    const float metresPerUv = 2.0f * baseHalfExtent;
    const float usable = static_cast<float>(tileSize - 2);  // one texel of snapping slack on each side
    int views = 0;
    float sliceNear = nearDepth;
    for (int c = 0; c < viewCascades; ++c) {
        const float i = static_cast<float>(c + 1) / static_cast<float>(viewCascades);
        const float logSplit = nearDepth * std::pow(farDepth / nearDepth, i);
        const float uniformSplit = nearDepth + (farDepth - nearDepth) * i;
        const float sliceFar = kPracticalSplitLambda * logSplit + (1.0f - kPracticalSplitLambda) * uniformSplit;
        glm::vec3 corners[8], centre(0.0f);
        for (int k = 0; k < 4; ++k) {
            corners[k] = at(k, sliceNear);
            corners[k + 4] = at(k, sliceFar);
        }
        for (const glm::vec3& p : corners) centre += p / 8.0f;
        float radius = 0.0f;
        glm::vec2 sliceUvLo(INFINITY), sliceUvHi(-INFINITY);
        for (const glm::vec3& p : corners) {
            radius = std::max(radius, glm::length(p - centre));
            const glm::vec4 clip = baseClipFromWorld * glm::vec4(p, 1.0f);
            const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
            sliceUvLo = glm::min(sliceUvLo, uv);
            sliceUvHi = glm::max(sliceUvHi, uv);
        }
        sliceNear = sliceFar;
        // The slice's bounding sphere (its size does not change as the camera turns), or the square
        // around the slice's light-space box clipped to the scene's where that is smaller.
        const glm::vec4 centreClip = baseClipFromWorld * glm::vec4(centre, 1.0f);
        glm::vec2 centreUv = glm::vec2(centreClip) / centreClip.w * 0.5f + 0.5f;
        const glm::vec2 clippedLo = glm::max(sliceUvLo, sceneUvLo), clippedHi = glm::min(sliceUvHi, sceneUvHi);
        if (!(clippedHi.x > clippedLo.x && clippedHi.y > clippedLo.y)) break;  // the slice misses the scene
        const float clippedRadius = 0.5f * std::max(clippedHi.x - clippedLo.x, clippedHi.y - clippedLo.y) * metresPerUv;
        if (clippedRadius < radius) {
            radius = clippedRadius;
            centreUv = 0.5f * (clippedLo + clippedHi);
        }
        radius = std::exp2(std::ceil(std::log2(std::max(radius, 1e-4f)) * kRadiusStepsPerOctave) / kRadiusStepsPerOctave);
        const float texelUv = 2.0f * radius / metresPerUv / usable;
        if (texelUv * static_cast<float>(tileSize) >= 1.0f) break;  // no finer than the scene's map
        const glm::vec2 origin = glm::floor((centreUv - 0.5f * texelUv * static_cast<float>(tileSize)) / texelUv) * texelUv;
        out.cascades[views++] = glm::vec4(origin, 1.0f / (texelUv * static_cast<float>(tileSize)), texelUv * metresPerUv);
    }
    return finish(views);
}

glm::mat4 cascadeAtlasClipFromWorld(const glm::mat4& baseClipFromWorld, const ShadowCascades& s, int c) {
    const float tiles = static_cast<float>(shadowAtlasTiles(s.count));
    const glm::vec2 tile(static_cast<float>(c % 2), static_cast<float>(c / 2));
    const glm::vec4 k = s.cascades[c];
    // atlas ndc = 2 (tile + (uv - origin) scale) / tiles - 1 with uv = 0.5 ndc + 0.5 (orthographic: w = 1)
    const float scale = k.z / tiles;
    const glm::vec2 offset = 2.0f * (tile + (0.5f - glm::vec2(k)) * k.z) / tiles - 1.0f;
    glm::mat4 m(1.0f);
    m[0][0] = scale;
    m[1][1] = scale;
    m[3][0] = offset.x;
    m[3][1] = offset.y;
    return m * baseClipFromWorld;
}

}  // namespace bounce::render
