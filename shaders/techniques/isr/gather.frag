// isr's gather as a stencilled draw (Nichols 2010 §4.2.1.2, gatherPass=stencil): one fragment per
// stencilled atlas texel of the level rectangle; the sum is isr/gather.glsl's. Output: atlas RGBA32F
// (alpha 1 = rendered here).
#include "techniques/isr/gather.glsl"
// Only the stencilled cells of the level rectangle may run the loop. This shader has no side effects,
// so GL already allows the stencil test before it (llvmpipe does it: same frame time with and without
// the qualifier); the qualifier makes it required, so a counter added here later cannot silently turn
// the culling off as it did in hisr's gather (see that file). Safe: no discard, no gl_FragDepth, KEEP.
layout(early_fragment_tests) in;
layout(location = 0) out vec4 o_irradiance;

void main() {
    uvec2 rays = uvec2(0u);
    vec3 irradiance = gatherCell(ivec2(gl_FragCoord.xy) - u_levelOrigin, u_level, rays);
    countVplRays(rays);
    o_irradiance = vec4(irradiance, 1.0);
}
