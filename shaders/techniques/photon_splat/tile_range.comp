// Photon splatting (bounce's optimisation of the splat pass, flux estimate only): the depth range of
// each bundle's first hits, from its tile of the depth atlas. Under the flux estimate only a first hit
// receives light, so splat.vert draws the volume cut to this range (plus a margin) instead of the
// whole volume. One work group per tile: each invocation takes the minimum and maximum over a strided
// share of the tile's texels (cleared texels, depth 1, hold no hit), then a tree reduction in shared
// memory. Output: ranges[bundle] = (lowest, highest) hit depth along w from P, metres; (1, 0) when
// no texel holds a hit.
#include "techniques/photon_splat/splat_shared.h"

layout(local_size_x = 64) in;
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer Bundles { BundleGpu b_bundles[]; };
layout(std430, binding = BINDING_SSBO_TECH2) writeonly buffer Ranges { vec2 r_ranges[]; };
layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_maps;
uniform int u_first;
uniform ivec2 u_tiles;
uniform int u_resolution;

shared float s_lo[64];
shared float s_hi[64];

void main() {
    int tile = int(gl_WorkGroupID.x);
    ivec2 corner = ivec2(tile % u_tiles.x, tile / u_tiles.x) * u_resolution;
    float lo = 1.0, hi = 0.0;
    for (int i = int(gl_LocalInvocationIndex); i < u_resolution * u_resolution; i += 64) {
        float d = texelFetch(s_maps, corner + ivec2(i % u_resolution, i / u_resolution), 0).r;
        if (d < 1.0) {
            lo = min(lo, d);
            hi = max(hi, d);
        }
    }
    s_lo[gl_LocalInvocationIndex] = lo;
    s_hi[gl_LocalInvocationIndex] = hi;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1u) {
        if (gl_LocalInvocationIndex < stride) {
            s_lo[gl_LocalInvocationIndex] = min(s_lo[gl_LocalInvocationIndex], s_lo[gl_LocalInvocationIndex + stride]);
            s_hi[gl_LocalInvocationIndex] = max(s_hi[gl_LocalInvocationIndex], s_hi[gl_LocalInvocationIndex + stride]);
        }
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) {
        BundleGpu b = b_bundles[u_first + tile];
        float zNear = b.right.w, zFar = b.up.w;
        r_ranges[u_first + tile] = s_lo[0] <= s_hi[0] ? zNear + vec2(s_lo[0], s_hi[0]) * (zFar - zNear) : vec2(1.0, 0.0);
    }
}
