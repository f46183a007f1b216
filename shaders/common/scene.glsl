// Scene data every scene-drawing pass reads: objects, materials, base-colour textures, the view.
#include "common/shared.h"

layout(std430, binding = BINDING_SSBO_OBJECTS) readonly buffer ObjectBlock { ObjectGpu u_objects[]; };
layout(std430, binding = BINDING_SSBO_MATERIALS) readonly buffer MaterialBlock { MaterialGpu u_materials[]; };
layout(std140, binding = BINDING_UBO_VIEW) uniform ViewBlock { ViewUniforms u_view; };
layout(binding = BINDING_TEX_BASECOLOR) uniform sampler2DArray s_baseColor;

vec3 materialAlbedo(uint material, vec2 uv) {
    MaterialGpu m = u_materials[material];
    vec3 albedo = m.baseColor.rgb;
    // Texture v runs down the stored image (row 0 = top), as in the reference (docs/scene.md).
    if (m.baseColor.a >= 0.0) albedo *= texture(s_baseColor, vec3(uv, m.baseColor.a)).rgb;
    return albedo;
}

// Emitted radiance: emission times the emission texture (a layer of the same array), if any.
vec3 materialEmission(uint material, vec2 uv) {
    MaterialGpu m = u_materials[material];
    vec3 emission = m.emission.rgb;
    if (m.emission.a >= 0.0) emission *= texture(s_baseColor, vec3(uv, m.emission.a)).rgb;
    return emission;
}
