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

// Alpha masking (glTF alphaMode MASK, docs/scene.md "Materials"): true where the surface is absent,
// coverage = factor * the coverage texture's red channel below the cutoff. Level 0, bilinear, as the
// reference reads it (TextureLookup.h), so both renderers cut the same outline; and textureLod needs no
// derivatives, so it may run after a discard, in geometry shaders and in non-uniform control flow.
bool materialMasked(uint material, vec2 uv) {
    MaterialGpu m = u_materials[material];
    if (m.alpha.x <= 0.0) return false;
    float coverage = m.alpha.y;
    if (m.alpha.z >= 0.0) coverage *= textureLod(s_baseColor, vec3(uv, m.alpha.z), 0.0).r;
    return coverage < m.alpha.x;
}

// The tangent-space normal map (glTF normalTexture) applied to the unit front-side normal n:
// normalize(T x + B y + N z) with T the tangent made orthogonal to n and B = w cross(n, T) (Scene.h
// Mesh::tangents); x and y scaled by the material's normal scale. n itself without a map or tangent.
vec3 materialNormal(uint material, vec2 uv, vec3 n, vec4 tangent) {
    MaterialGpu m = u_materials[material];
    if (m.maps.x < 0.0 || tangent.w == 0.0) return n;
    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
    if (dot(t, t) <= 0.0) return n;
    t = normalize(t);
    vec3 b = tangent.w * cross(n, t);
    vec3 s = texture(s_baseColor, vec3(uv, m.maps.x)).rgb * 2.0 - 1.0;
    s.xy *= m.maps.y;
    vec3 mapped = t * s.x + b * s.y + n * s.z;
    return dot(mapped, mapped) > 0.0 ? normalize(mapped) : n;
}

// Roughness and metallic: the factors times the metallic-roughness texture's G and B (glTF).
vec2 materialRoughnessMetallic(uint material, vec2 uv) {
    MaterialGpu m = u_materials[material];
    vec2 rm = m.params.xy;
    if (m.maps.z >= 0.0) rm *= texture(s_baseColor, vec3(uv, m.maps.z)).gb;
    return rm;
}
