#pragma once
// The view-fitted cascades of a directional light's shadow map (docs/rendering.md "Shadows"): pure
// geometry, no GL. The whole-scene orthographic map (the light's shadowClipFromWorld, as before the
// cascades) stays the last cascade, so every point of the scene has a map (VCT's injection and
// radiosity's elements sample it outside the camera's view); the cascades in front of it cover slices
// of the camera's view frustum, clipped to the scene's depth range, at finer texels.
#include "common/shared.h"
#include "render/SceneDrawer.h"

#include <array>

namespace bounce::render {

struct ShadowCascades {
    // LightGpu::shadowCascades: xy origin and z scale in the whole-scene map's [0,1]^2, w texel size (m).
    std::array<glm::vec4, SHADOW_MAX_CASCADES> cascades{};
    int count = 1;  // view cascades + the whole-scene one
};

// baseClipFromWorld: the whole-scene orthographic map's clip-from-world, which spans 2 * baseHalfExtent
// metres per side; viewCascades (0 .. SHADOW_MAX_CASCADES - 1): slices of `camera`'s frustum to fit;
// tileSize: texels per side of each cascade. Cascades that would be no finer than the scene's map are
// dropped. Texel sizes change only in steps of kRadiusStep and origins are snapped to whole texels,
// so a moving camera does not make shadow edges shimmer.
ShadowCascades fitShadowCascades(const glm::mat4& baseClipFromWorld, float baseHalfExtent, const View& camera,
                                 glm::vec3 sceneLo, glm::vec3 sceneHi, int viewCascades, int tileSize);

// The clip-from-world that renders cascade c into its tile of the 2 x 2 atlas (1 x 1 with one cascade).
glm::mat4 cascadeAtlasClipFromWorld(const glm::mat4& baseClipFromWorld, const ShadowCascades& s, int c);

// The atlas's tiles per side: 1 with the whole-scene map alone, else 2 (matches common/lighting.glsl).
inline int shadowAtlasTiles(int count) { return count > 1 ? 2 : 1; }

}  // namespace bounce::render
