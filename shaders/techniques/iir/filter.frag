// Geometry-aware n x m box filter (Laine et al. 2007 §5.2, Fig. 5): average the irradiance of the
// pixels in an n x m window (x in [0, n-1], y in [0, m-1], offset by floor(n/2), floor(m/2), so each
// interleave residue appears once) whose position is within alpha and whose normal has a dot
// product above beta with the centre's; then reflect it: L = albedo (1 - metallic) E / pi.
// Inputs: irradiance (INPUT0), G-buffer, u_tiles, u_alpha (metres), u_beta, u_imageSize.
// Output: indirect radiance W/(m^2 sr).
#include "common/gbuffer.glsl"
#include "common/constants.glsl"
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_irradiance;
uniform ivec2 u_tiles;
uniform ivec2 u_imageSize;
uniform float u_alpha;
uniform float u_beta;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    Surface c = readSurface(pixel);
    o_radiance = vec4(0.0, 0.0, 0.0, 1.0);
    if (!c.covered) return;
    vec3 sum = vec3(0.0);
    float count = 0.0;
    ivec2 halfWindow = u_tiles / 2;
    for (int y = 0; y < u_tiles.y; ++y) {
        for (int x = 0; x < u_tiles.x; ++x) {
            ivec2 q = pixel + ivec2(x, y) - halfWindow;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_imageSize))) continue;
            Surface s = readSurface(q);
            if (!s.covered) continue;
            if (distance(s.position, c.position) < u_alpha && dot(s.normal, c.normal) > u_beta) {
                sum += texelFetch(s_irradiance, q, 0).rgb;
                count += 1.0;
            }
        }
    }
    vec3 irradiance = count > 0.0 ? sum / count : texelFetch(s_irradiance, pixel, 0).rgb;
    o_radiance = vec4((1.0 - c.metallic) * c.albedo * irradiance * kInvPi, 1.0);
}
