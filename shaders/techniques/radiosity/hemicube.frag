// van de Hoef 2013: what a hemicube pixel holds. Host define RAD_HC_MODE:
//   0 ID hemicube (sec. 4.3, R32UI): the surface ID + 1 (0 = nothing) of the seen quad, for the
//     visibility tests (the thesis's quad IDs: its quads are whole coplanar surfaces);
//   1 radiosity hemicube (gather, Alg. 4.1; RGBA16F): B of the seen element, bilinear;
//   2 combined ID + shot hemicube (Alg. 4.4 line 7): the ID and the shot radiosity B - Bu of the
//     static quads C (moving quads M occlude with 0: R_g(C, M) gathers from C only);
//   3 back shot hemicube (Alg. 4.4 lines 8-9; RGBA16F, 4x MSAA): rgb the shot radiosity of C, a the
//     distance from the hemicube's origin (the depth of REPROJECT).
// Patches are one-sided: a back face occludes but contributes no radiosity.
#include "common/scene.glsl"
#include "techniques/radiosity/patch.glsl"
#include "techniques/radiosity/hemicube.glsl"

layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_total;   // B
layout(binding = BINDING_TEX_TECH1) uniform sampler2D s_unshot;  // Bu
uniform uint u_hemicube;
uniform vec2 u_atlasSize;

in vec3 g_posWorld;
in vec2 g_st;
flat in uint g_quad;
flat in vec3 g_normalWorld;
in vec2 g_uv;
flat in uint g_material;

#if RAD_HC_MODE == 0
layout(location = 0) out uint o_id;
#elif RAD_HC_MODE == 1
layout(location = 0) out vec4 o_radiance;
#elif RAD_HC_MODE == 2
layout(location = 0) out uint o_id;
layout(location = 1) out vec4 o_shot;
#else
layout(location = 0) out vec4 o_shotDistance;
#endif

void main() {
    RadHemicubeGpu h = u_hemicubes[u_hemicube];
    bool front = dot(g_normalWorld, h.origin.xyz - g_posWorld) > 0.0;
#if RAD_HC_MODE == 0 || RAD_HC_MODE == 2
    o_id = g_quad == RAD_NO_QUAD ? 0u : u_quads[g_quad].info.w + 1u;
#endif
    vec3 total = vec3(0.0), shot = vec3(0.0);
    if (g_quad != RAD_NO_QUAD && front) {
        RadQuadGpu q = u_quads[g_quad];
        vec2 uv = radAtlasUv(q, clamp(g_st, 0.0, 1.0), u_atlasSize);
        total = texture(s_total, uv).rgb;
        if (!radBodyMoving(q.info.x)) shot = total - texture(s_unshot, uv).rgb;
    }
    // An alpha-masked texel is no surface: it neither occludes nor is seen (after the lookups above).
    if (g_material != RAD_NO_MATERIAL && materialMasked(g_material, g_uv)) discard;
#if RAD_HC_MODE == 1
    o_radiance = vec4(total, 1.0);
#elif RAD_HC_MODE == 2
    o_shot = vec4(shot, 1.0);
#elif RAD_HC_MODE == 3
    o_shotDistance = vec4(shot, length(g_posWorld - h.origin.xyz));
#endif
}
