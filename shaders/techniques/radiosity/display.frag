// van de Hoef 2013 sec. 4.1 / Fig. 4.1.1: the final display. Quads are drawn with their total
// radiosity texture B, bilinearly filtered (the texel centres on the edges make it continuous across
// quads), or nearest-filtered for the debug view (u_nearest). Emitters are part of the solution (no separate
// direct pass): o_direct gets the emitted radiance E, o_indirect the reflected part B - E, so
// full = B.
#include "common/scene.glsl"
#include "techniques/radiosity/patch.glsl"

layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_total;
uniform vec2 u_atlasSize;
uniform int u_nearest;

in vec3 g_posWorld;
in vec2 g_st;
flat in uint g_quad;
flat in vec3 g_normalWorld;
in vec2 g_uv;
flat in uint g_material;

layout(location = 0) out vec4 o_direct;
layout(location = 1) out vec4 o_indirect;

void main() {
    o_direct = vec4(0.0, 0.0, 0.0, 1.0);
    o_indirect = vec4(0.0, 0.0, 0.0, 1.0);
    // An alpha-masked texel is no surface: what lies behind it shows. Discarded last, after the atlas
    // lookup's derivatives (GLSL: none after a discard).
    bool masked = g_material != RAD_NO_MATERIAL && materialMasked(g_material, g_uv);
    if (g_quad == RAD_NO_QUAD || dot(g_normalWorld, u_view.eyePosition.xyz - g_posWorld) <= 0.0) {  // one-sided patches
        if (masked) discard;
        return;
    }
    RadQuadGpu q = u_quads[g_quad];
    vec2 st = clamp(g_st, 0.0, 1.0);
    vec3 b = u_nearest != 0 ? texelFetch(s_total, ivec2(floor(vec2(q.atlas.xy) + 0.5 + st * vec2(q.atlas.zw - 1u))), 0).rgb
                            : texture(s_total, radAtlasUv(q, st, u_atlasSize)).rgb;
    o_direct.rgb = q.emission.rgb;
    o_indirect.rgb = max(b - q.emission.rgb, vec3(0.0));
    if (masked) discard;
}
