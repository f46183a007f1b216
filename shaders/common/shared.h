// Structures shared by C++ and GLSL (uniform and storage blocks). Written once: C++ includes this
// file with glm types aliased, GLSL gets it through #include. Members are only vec4, uvec4, ivec4
// and mat4, so std140 and std430 layouts equal the C++ layout (checked by static_asserts in C++).
#ifndef BOUNCE_SHARED_H
#define BOUNCE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace bounce::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#endif

// One placed mesh. normalFromObject is the inverse transpose of worldFromObject's upper 3x3.
struct ObjectGpu {
    mat4 worldFromObject;
    mat4 normalFromObject;
    uvec4 info;  // x: material index, y: 1 if dynamic, z: object index, w: unused
};

struct MaterialGpu {
    vec4 baseColor;  // rgb: albedo, a: texture layer in the base-colour array, or -1
    vec4 emission;   // rgb: emitted radiance W/(m^2 sr); a: its texture's layer in the same array, or -1
    vec4 params;     // x: roughness, y: metallic, z: specularF0, w: 1 if two-sided
    vec4 alpha;      // x: alpha cutoff (0: opaque), y: coverage factor, z: coverage texture layer or -1
    vec4 maps;       // x: normal map layer or -1, y: normal scale, z: metallic-roughness layer or -1
};

// The view a pass renders from (camera, light, cube or hemicube face).
struct ViewUniforms {
    mat4 clipFromWorld;
    mat4 viewFromWorld;
    vec4 eyePosition;  // xyz: world position; w: far distance (for distance maps)
    vec4 params;       // x: viewport width, y: viewport height, z: near, w: draw filter
};

// Tiles of a directional light's shadow atlas (2 x 2): view-fitted cascades plus the whole-scene map.
#define SHADOW_MAX_CASCADES 4

#define LIGHT_POINT 0
#define LIGHT_SPOT 1
#define LIGHT_DIRECTIONAL 2
#define LIGHT_AREA 3

struct LightGpu {
    vec4 position;   // xyz: world position (area: centre); w: light type
    vec4 direction;  // xyz: spot axis / directional propagation; w: cos(cutoff)
    vec4 emission;   // rgb: intensity W/sr (point, spot), irradiance W/m^2 (directional),
                     //      radiance W/(m^2 sr) (area); w: spot falloff exponent
    vec4 edgeU;      // area light full edge vectors (xyz); w: shadow kind (0 none, 1 2D, 2 cube)
    vec4 edgeV;      // w: shadow bias (metres, along the normal)
    mat4 shadowClipFromWorld;  // 2D shadow maps
    vec4 shadowParams;         // x: far distance of cube distance maps, y: map size (one cascade's tile), z: PCF
                               // radius (texels), w: 2D maps: cascades in the map (docs/rendering.md "Shadows")
    vec4 shadowOrigin;         // xyz: centre of the cube distance map (area lights: just off the emitter)
    // 2D maps, per cascade c < shadowParams.w, finest first, the last one the whole scene: xy: the
    // cascade's origin in the shadowClipFromWorld map's [0,1]^2, z: its scale (cascade uv = (uv - xy) * z);
    // w: the world size of one texel (metres; spot lights: metres per metre of distance from the light).
    vec4 shadowCascades[SHADOW_MAX_CASCADES];
    vec4 area;                 // area lights: rgb radiance W/(m^2 sr) before the texture (emission.rgb is
                               // radiance times the texture's mean); w: flags AREA_TEXTURED | AREA_TWO_SIDED
};
#define AREA_TEXTURED 1
#define AREA_TWO_SIDED 2

struct FrameUniforms {
    mat4 clipFromWorld;
    mat4 worldFromClip;
    mat4 viewFromWorld;
    vec4 eyePosition;  // xyz; w: time (s)
    vec4 viewport;     // x: width, y: height, z: 1/width, w: 1/height
    vec4 ambient;      // rgb: ambient radiance of the `ambient` baseline; w: frame index
};

#ifdef __cplusplus
static_assert(sizeof(ObjectGpu) == 144);
static_assert(sizeof(MaterialGpu) == 80);
static_assert(sizeof(ViewUniforms) == 160);
static_assert(sizeof(LightGpu) == 192 + SHADOW_MAX_CASCADES * 16);
static_assert(sizeof(FrameUniforms) == 240);
}  // namespace bounce::gpu
#endif

#endif
