// Photon splatting (seed 004, §3.4/§4.3 normalisation, §4.4 combine; bounce's debug views): the
// accumulation becomes indirect radiance. Normalised estimate: exposure * sum(w S V) / sum(w), and
// the ambient radiance where no bundle reached (zero weight). Flux estimate: the sum itself. Debug:
// 1 overlap heat map (bundles per pixel, blue 0 -> red u_heatMax), 2 the accumulation before
// normalisation, 3 the stratification grid cell of each pixel in hashed colours (Fig. 9).
#include "common/gbuffer.glsl"
#include "techniques/photon_splat/splat_shared.h"

layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_accum;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2D s_stats;
uniform int u_estimate;
uniform float u_exposure;
uniform vec3 u_ambient;  // W/(m^2 sr)
uniform int u_view;
uniform float u_heatMax;
uniform vec3 u_gridLo, u_gridHi;
uniform int u_gridSize;
layout(location = 0) out vec4 o_radiance;

vec3 hashColour(uint n) {
    n = (n ^ 61u) ^ (n >> 16);
    n *= 9u;
    n ^= n >> 4;
    n *= 0x27d4eb2du;
    n ^= n >> 15;
    return vec3(n & 255u, (n >> 8) & 255u, (n >> 16) & 255u) / 255.0;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(s_accum, p, 0);
    vec4 st = texelFetch(s_stats, p, 0);
    Surface s = readSurface(p);
    if (u_view == 1) {
        float t = clamp(st.r / u_heatMax, 0.0, 1.0);
        o_radiance = vec4(mix(mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0), clamp(2.0 * t, 0.0, 1.0)), vec3(1.0, 0.0, 0.0),
                              clamp(2.0 * t - 1.0, 0.0, 1.0)) * (st.r > 0.0 ? 1.0 : 0.0), 1.0);
        return;
    }
    if (u_view == 2) { o_radiance = vec4(a.rgb, 1.0); return; }
    if (u_view == 3) {
        if (!s.covered) { o_radiance = vec4(0.0); return; }
        ivec3 c = ivec3(floor((s.position - u_gridLo) / max(u_gridHi - u_gridLo, vec3(1e-6)) * float(u_gridSize)));
        o_radiance = vec4(hashColour(uint(c.x + u_gridSize * (c.y + u_gridSize * c.z))), 1.0);
        return;
    }
    if (!s.covered) { o_radiance = vec4(0.0); return; }
    if (u_estimate == SPLAT_ESTIMATE_FLUX) { o_radiance = vec4(a.rgb, 1.0); return; }
    vec3 albedo = (1.0 - s.metallic) * s.albedo;
    o_radiance = vec4(a.a > 0.0 ? u_exposure * a.rgb / a.a : u_ambient * albedo, 1.0);
}
