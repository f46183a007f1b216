// Geometry-aware filter of the combined interleaved irradiance (Laine et al. 2007 §5.2, Fig. 5), then
// the receiver's reflection L = albedo (1 - metallic) E / pi. A tap q of the window around pixel p
// counts when |p_q - p_p| < alpha and n_q . n_p > beta; the kept taps' weighted mean is the irradiance
// (the centre always passes).
// - u_tent = 0, the paper's box: an n x m window (x in [0, n-1], y in [0, m-1], offset by floor(n/2),
//   floor(m/2)), weight 1, so each interleave residue appears once. Where one residue's VPLs carry most
//   of the light's gradient (a few VPLs near the receiver, the tiles' VPL sets not alike) the output
//   changes only when that residue's tap jumps by n pixels: stair-steps of period n.
// - u_tent = 1 (bounce's default, docs/techniques/iir.md "Filter"): a (2n-1) x (2m-1) window centred on
//   p with tent weights (n - |x|)(m - |y|). Each residue appears at two offsets per axis whose weights
//   sum to n per axis, so with every tap kept each residue (VPL subset) still weighs 1/(n m), and the
//   output interpolates each subset's sub-image linearly instead of holding it: no stair-steps.
// Inputs: irradiance (INPUT0), G-buffer, u_tiles, u_alpha (metres), u_beta, u_tent, u_imageSize.
// Output: indirect radiance W/(m^2 sr).
#include "common/gbuffer.glsl"
#include "common/constants.glsl"
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_irradiance;
uniform ivec2 u_tiles;
uniform ivec2 u_imageSize;
uniform float u_alpha;
uniform float u_beta;
uniform int u_tent;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    Surface c = readSurface(pixel);
    o_radiance = vec4(0.0, 0.0, 0.0, 1.0);
    if (!c.covered) return;
    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    // Box: offsets [-floor(n/2), n - 1 - floor(n/2)]; tent: [-(n-1), n-1].
    ivec2 lo = u_tent != 0 ? 1 - u_tiles : -(u_tiles / 2);
    ivec2 hi = u_tent != 0 ? u_tiles - 1 : u_tiles - 1 - u_tiles / 2;
    for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
            ivec2 q = pixel + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_imageSize))) continue;
            vec4 position = texelFetch(s_gPosition, q, 0);
            if (position.w <= 0.5) continue;
            vec3 normal = normalize(texelFetch(s_gNormal, q, 0).xyz + vec3(0.0, 0.0, 1e-12));
            if (distance(position.xyz, c.position) < u_alpha && dot(normal, c.normal) > u_beta) {
                float w = u_tent != 0 ? float((u_tiles.x - abs(x)) * (u_tiles.y - abs(y))) : 1.0;
                sum += w * texelFetch(s_irradiance, q, 0).rgb;
                weightSum += w;
            }
        }
    }
    vec3 irradiance = weightSum > 0.0 ? sum / weightSum : texelFetch(s_irradiance, pixel, 0).rgb;
    o_radiance = vec4((1.0 - c.metallic) * c.albedo * irradiance * kInvPi, 1.0);
}
