// van de Hoef 2013 sec. 4.1 / Fig. 4.1.1: the final display. Quads are drawn with their total
// radiosity texture B, bilinearly filtered (the texel centres on the edges make it continuous across
// quads), or nearest-filtered for the debug view (u_nearest). Emitters are part of the solution (no separate
// direct pass): o_direct gets the emitted radiance E, o_indirect the reflected part B - E - D, so
// full = B where the scene has only emitters. D is the direct light of point, spot and directional
// lights at the elements (bounce's extension): the host adds it per pixel to o_direct (the shared
// direct pass's shadow-mapped light), so full = E + direct(pixel) + (B - E - D).
#include "common/scene.glsl"
#include "techniques/radiosity/patch.glsl"

layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_total;
layout(binding = BINDING_TEX_TECH1) uniform sampler2D s_light;  // D (1x1 zero without punctual lights)
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
    ivec2 texel = ivec2(floor(vec2(q.atlas.xy) + 0.5 + st * vec2(q.atlas.zw - 1u)));
    vec2 uv = radAtlasUv(q, st, u_atlasSize);
    bool oneTexel = textureSize(s_light, 0).x == 1;
    vec3 b = u_nearest != 0 ? texelFetch(s_total, texel, 0).rgb : textureLod(s_total, uv, 0.0).rgb;  // one level: no derivatives (a discard precedes)
    vec3 d = oneTexel ? vec3(0.0) : u_nearest != 0 ? texelFetch(s_light, texel, 0).rgb : textureLod(s_light, uv, 0.0).rgb;
    o_direct.rgb = q.emission.rgb;
    o_indirect.rgb = max(b - q.emission.rgb - d, vec3(0.0));
    if (masked) discard;
}
