// Per-tile accumulation (Laine et al. 2007 §5.1): irradiance at an atlas pixel from the VPLs of its
// tile, with paraboloid shadow lookups and the per-VPL irradiance clamp; no receiver albedo.
//   E = n*m * sum_i min(I_i cos(theta_i) cos(theta_x) / d^2, I_i / d_c^2) * V_i
// (I_i = rho_i Phi_i / pi, W/sr; the factor n*m makes the average over the n*m tiles, taken by the
// filter, the sum over all VPLs.)
// Inputs: split atlas (INPUT0 position, INPUT1 normal), VPLs (SSBO TECH0), tile lists (SSBO TECH1),
// paraboloid maps (TECH0, sampler2DArrayShadow), u_maxGeometry = 1/d_c^2, u_far, u_depthBias
// (fraction of u_far), u_normalOffset (metres). Output: irradiance W/m^2 (rgb).
#include "techniques/paraboloid/paraboloid.glsl"
struct VplGpu {
    vec4 position;   // w: shadow-map layer
    vec4 normal;
    vec4 tangent;
    vec4 intensity;  // W/sr along the normal
};
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { VplGpu u_vpls[]; };
// [0, tiles]: offsets into this array of each tile's list of VPL indices; the lists follow.
layout(std430, binding = BINDING_SSBO_TECH1) readonly buffer TileBlock { uint u_tileData[]; };
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_position;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2D s_normal;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArrayShadow s_paraboloid;

uniform ivec2 u_tiles;
uniform ivec2 u_tileSize;
uniform float u_maxGeometry;
uniform float u_far;
uniform float u_depthBias;
uniform float u_normalOffset;

layout(location = 0) out vec4 o_irradiance;

void main() {
    ivec2 atlas = ivec2(gl_FragCoord.xy);
    vec4 p = texelFetch(s_position, atlas, 0);
    o_irradiance = vec4(0.0, 0.0, 0.0, 1.0);
    if (p.w < 0.5) return;
    vec3 nx = normalize(texelFetch(s_normal, atlas, 0).xyz);
    ivec2 tile = atlas / u_tileSize;
    uint t = uint(tile.y * u_tiles.x + tile.x);
    uint first = u_tileData[t], last = u_tileData[t + 1u];
    vec3 x = p.xyz + nx * u_normalOffset;
    vec3 irradiance = vec3(0.0);
    for (uint k = first; k < last; ++k) {
        VplGpu v = u_vpls[u_tileData[k]];
        vec3 toX = x - v.position.xyz;
        float d2 = max(dot(toX, toX), 1e-12);
        float d = sqrt(d2);
        vec3 w = toX / d;
        float cosV = dot(v.normal.xyz, w);
        float cosX = -dot(nx, w);
        if (cosV <= 0.0 || cosX <= 0.0) continue;
        float geometry = min(cosV * cosX / d2, u_maxGeometry);
        float visibility = paraboloidVisibility(s_paraboloid, v.position.w, w, d, v.normal.xyz, v.tangent.xyz, u_far, u_depthBias);
        irradiance += v.intensity.rgb * geometry * visibility;
    }
    o_irradiance = vec4(irradiance * float(u_tiles.x * u_tiles.y), 1.0);
}
